// The modal objectives solved for parameters (modal_solve.hpp): the log-scale Levenberg-Marquardt fit of
// mass/stiffness parameters and the damping least squares.
#include "modal_solve.hpp"

#include "numerics/levenberg_marquardt.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <string>

namespace mbgen::methods {

namespace {

bool within_bounds(const ModelInfo& info, const Eigen::VectorXd& p, const std::vector<int>& which) {
  for (int i : which) {
    const ParameterInfo& q = info.parameters[static_cast<std::size_t>(i)];
    if (!(p[i] >= q.lower && p[i] <= q.upper)) return false;
  }
  return true;
}

const IdentifiedMode& reference_of(const ModalProblem& pr, int m) {
  const ModeRef& mr = pr.modes[static_cast<std::size_t>(m)];
  return pr.configurations[static_cast<std::size_t>(mr.configuration)].reference[static_cast<std::size_t>(mr.mode)];
}

// Every reference mode's model damping ratio at q (global order); false when a configuration's modes cannot be
// paired.
bool damping_ratios(const ModalProblem& pr, const Eigen::VectorXd& q, Eigen::VectorXd& zeta) {
  const std::vector<bool> every(pr.configurations.size(), true);
  const std::vector<ModalComparison> cmp = compare_all(pr, q, every);
  for (const ModalComparison& c : cmp)
    if (!c.ok) return false;
  const auto nr = static_cast<Eigen::Index>(pr.modes.size());
  zeta.resize(nr);
  for (Eigen::Index m = 0; m < nr; ++m) {
    const ModeRef& mr = pr.modes[static_cast<std::size_t>(m)];
    zeta[m] = cmp[static_cast<std::size_t>(mr.configuration)].zeta[static_cast<std::size_t>(mr.mode)];
  }
  return true;
}

}  // namespace

namespace {

// The objectives at x = log(parameters `which`), the others at `base`; false outside the bounds.
bool objectives_at_log(const ModelInfo& info, const ParameterObjectives& f, const Eigen::VectorXd& base,
                       const std::vector<int>& which, const Eigen::VectorXd& x, Eigen::VectorXd& r) {
  Eigen::VectorXd p = base;
  for (std::size_t j = 0; j < which.size(); ++j) p[which[j]] = std::exp(x[static_cast<Eigen::Index>(j)]);
  if (!within_bounds(info, p, which)) return false;
  return f(p, r);
}

// Forward differences in x (backward where the forward step leaves the bounds).
bool jacobian_at_log(const ModelInfo& info, const ParameterObjectives& f, const Eigen::VectorXd& base,
                     const std::vector<int>& which, const Eigen::VectorXd& x, const Eigen::VectorXd& r,
                     Eigen::MatrixXd& J) {
  J.resize(r.size(), x.size());
  Eigen::VectorXd rh;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    constexpr double h = 1e-7;
    Eigen::VectorXd xh = x;
    xh[j] += h;
    double step = h;
    if (!objectives_at_log(info, f, base, which, xh, rh)) {
      xh[j] = x[j] - h;
      step = -h;
      if (!objectives_at_log(info, f, base, which, xh, rh)) return false;
    }
    J.col(j) = (rh - r) / step;
  }
  return true;
}

ParameterObjectives modal_objectives(const ModalProblem& pr, const std::vector<int>& modes) {
  return [&pr, &modes](const Eigen::VectorXd& p, Eigen::VectorXd& r) { return objectives_at(pr, p, modes, r); };
}

}  // namespace

bool residuals_at(const ModalProblem& pr, const Eigen::VectorXd& base, const std::vector<int>& which,
                  const std::vector<int>& modes, const Eigen::VectorXd& x, Eigen::VectorXd& r) {
  return objectives_at_log(pr.model.info(), modal_objectives(pr, modes), base, which, x, r);
}

LocalOptimum log_scale_fit(const ModelInfo& info, const ParameterObjectives& objectives, const Eigen::VectorXd& base,
                           const Eigen::VectorXd& start, const std::vector<int>& which, const FitOptions& options) {
  const estimation::ResidualFunction f = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    if (!objectives_at_log(info, objectives, base, which, x, r)) return false;
    return !J || jacobian_at_log(info, objectives, base, which, x, r, *J);
  };
  Eigen::VectorXd x0(static_cast<Eigen::Index>(which.size()));
  for (std::size_t j = 0; j < which.size(); ++j) x0[static_cast<Eigen::Index>(j)] = std::log(start[which[j]]);
  estimation::LmOptions lm;
  lm.max_iterations = options.max_iterations;
  lm.cost_tolerance = options.cost_tolerance;
  lm.step_tolerance = options.step_tolerance;
  lm.gradient_tolerance = options.gradient_tolerance;
  const estimation::LmResult res = estimation::levenberg_marquardt(f, x0, lm);
  LocalOptimum o;
  o.p = base;
  for (std::size_t j = 0; j < which.size(); ++j) o.p[which[j]] = std::exp(res.x[static_cast<Eigen::Index>(j)]);
  o.cost = res.cost;
  o.converged = res.converged;
  o.iterations = res.iterations;
  return o;
}

bool log_scale_jacobian(const ModelInfo& info, const ParameterObjectives& f, const Eigen::VectorXd& p,
                        const std::vector<int>& which, Eigen::VectorXd& r, Eigen::MatrixXd& J) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(which.size()));
  for (std::size_t j = 0; j < which.size(); ++j) x[static_cast<Eigen::Index>(j)] = std::log(p[which[j]]);
  return objectives_at_log(info, f, p, which, x, r) && jacobian_at_log(info, f, p, which, x, r, J);
}

LocalOptimum local_fit(const ModalProblem& pr, const Eigen::VectorXd& base, const Eigen::VectorXd& start,
                       const std::vector<int>& which, const std::vector<int>& modes, const FitOptions& options) {
  return log_scale_fit(pr.model.info(), modal_objectives(pr, modes), base, start, which, options);
}

ParameterClasses classify_parameters(const Model& model, const Eigen::VectorXd& prior,
                                     const std::vector<int>& candidates) {
  ModelDerivatives d;
  model.derivatives(prior, d);
  const ModelInfo& info = model.info();
  auto touches = [](const std::vector<DerivativeEntry>& list, int i) {
    return std::any_of(list.begin(), list.end(),
                       [&](const DerivativeEntry& e) { return e.param == i && e.value != 0; });
  };
  ParameterClasses out;
  for (int i : candidates) {
    const std::string& name = info.parameters[static_cast<std::size_t>(i)].name;
    const bool mk = touches(d.M, i) || touches(d.K, i), c = touches(d.C, i);
    if (touches(d.B, i) || touches(d.Cd, i) || touches(d.Cv, i) || touches(d.Ca, i))
      out.other.push_back({i, "fit: error: --method modal fits mass, stiffness and damping parameters to modes, but " +
                                  name + " enters the input or output map"});
    else if (mk && c)
      out.other.push_back({i, "fit: error: --method modal needs each parameter to act on damping alone or on "
                              "mass/stiffness alone (Ellinger & Zaeh's assumption A1), but " +
                                  name + " acts on both"});
    else if (!mk && !c)
      out.other.push_back({i, "fit: error: --method modal: " + name + " acts on none of M, C, K at its prior value"});
    else if (mk && !(prior[i] > 0))
      out.other.push_back({i, "fit: error: --method modal searches mass/stiffness parameters on a log scale and needs "
                              "a positive prior, but " +
                                  name + " = " + std::to_string(prior[i])});
    else
      (mk ? out.structural : out.damping).push_back(i);
  }
  return out;
}

void solve_damping(const ModalProblem& pr, const std::vector<int>& damping, const Eigen::VectorXd& prior,
                   int iterations, Eigen::VectorXd& p, nlohmann::json& log) {
  if (damping.empty()) return;
  const auto nr = static_cast<Eigen::Index>(pr.modes.size());
  Eigen::VectorXd zeta_ref(nr);
  for (Eigen::Index r = 0; r < nr; ++r) zeta_ref[r] = reference_of(pr, static_cast<int>(r)).zeta;
  const DampingRatios ratios = [&pr](const Eigen::VectorXd& q, Eigen::VectorXd& zeta) {
    return damping_ratios(pr, q, zeta);
  };
  solve_damping_ratios(pr.model.info(), ratios, zeta_ref, zeta_ref, damping, prior, iterations,
                       "fit: error: --method modal", hz_list(pr.configurations), p, log);
}

void solve_damping_ratios(const ModelInfo& info, const DampingRatios& ratios, const Eigen::VectorXd& zeta_ref,
                          const Eigen::VectorXd& row_scale, const std::vector<int>& damping,
                          const Eigen::VectorXd& prior, int iterations, const std::string& what,
                          const std::string& modes_text, Eigen::VectorXd& p, nlohmann::json& log,
                          Eigen::MatrixXd* weighted_q) {
  if (damping.empty()) return;
  const auto kd = static_cast<Eigen::Index>(damping.size());
  const Eigen::Index nr = zeta_ref.size();
  for (int it = 0; it < iterations; ++it) {
    Eigen::VectorXd z0, z1;
    if (!ratios(p, z0)) throw FitError(what + ": the model's modes could not be paired at the estimate");
    Eigen::MatrixXd Q(nr, kd);
    Eigen::VectorXd rhs(nr), c(kd);
    for (Eigen::Index j = 0; j < kd; ++j) {
      const int i = damping[static_cast<std::size_t>(j)];
      c[j] = p[i];
      const double h = 1e-3 * std::max({std::abs(p[i]), std::abs(prior[i]), 1e-6});
      Eigen::VectorXd q = p;
      q[i] += h;
      if (!ratios(q, z1)) throw FitError(what + ": the model's modes could not be paired at the estimate");
      Q.col(j) = (z1 - z0) / h;
    }
    Eigen::VectorXd residual_share(nr);
    for (Eigen::Index r = 0; r < nr; ++r) {
      residual_share[r] = z0[r] - Q.row(r).dot(c);
      rhs[r] = (zeta_ref[r] - residual_share[r]) / row_scale[r];
      Q.row(r) /= row_scale[r];
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Q);
    if (qr.rank() < kd)
      throw FitError(what + ": the modal damping ratios of the " + std::to_string(nr) + " identified modes (" +
                     modes_text + ") cannot separate the damping parameters (rank " + std::to_string(qr.rank()) +
                     " of " + std::to_string(kd) + ")");
    const Eigen::VectorXd sol = qr.solve(rhs);
    double step = 0;
    for (Eigen::Index j = 0; j < kd; ++j) {
      const int i = damping[static_cast<std::size_t>(j)];
      const ParameterInfo& q = info.parameters[static_cast<std::size_t>(i)];
      const double v = std::min(std::max(sol[j], q.lower), q.upper);
      step = std::max(step, std::abs(v - p[i]) / std::max(std::abs(v), 1e-300));
      p[i] = v;
    }
    log.push_back({{"relative_step", step}, {"ndd_residual_norm", (Q * sol - rhs).norm()}});
    if (weighted_q) *weighted_q = Q;
  }
}

}  // namespace mbgen::methods
