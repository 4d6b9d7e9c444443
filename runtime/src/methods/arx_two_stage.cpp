#include "mbgen/methods/arx_two_stage.hpp"

#include "method_result.hpp"
#include "method_setup.hpp"

#include "numerics/levenberg_marquardt.hpp"

#include "mbgen/estimation/identifiability.hpp"
#include "numerics/constants.hpp"
#include "numerics/state_eigen.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace mbgen {

namespace {

using methods::MethodSetup;

const char* const kMethod = "arx-two-stage";

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The measured displacement outputs of a record and the map from them to the coordinates, q = G y.
struct Coordinates {
  std::vector<int> outputs;  // model output indices (pure displacement outputs present in the record)
  Eigen::MatrixXd G;         // n x outputs
};

Coordinates coordinates_from(const Model& model, const MethodSetup& setup, const ModelMatrices& m,
                             const ModelDerivatives& d, const TimeRecord& t) {
  const ModelInfo& info = model.info();
  const auto n = static_cast<Eigen::Index>(info.coordinates.size());
  const std::set<int> estimated(setup.candidates.begin(), setup.candidates.end());
  Coordinates c;
  std::vector<std::string> dependent;
  for (std::size_t o = 0; o < info.outputs.size(); ++o) {
    const auto row = static_cast<Eigen::Index>(o);
    if (!t.find(info.outputs[o]) || m.Cd.row(row).isZero(0) || !m.Cv.row(row).isZero(0) || !m.Ca.row(row).isZero(0))
      continue;
    bool depends = false;
    for (const DerivativeEntry& e : d.Cd)
      if (e.row == static_cast<int>(o) && estimated.count(e.param)) depends = true;
    if (depends) {
      dependent.push_back(info.outputs[o]);
      continue;
    }
    c.outputs.push_back(static_cast<int>(o));
  }
  if (!dependent.empty())
    throw FitError(t.file + ": error: --method arx-two-stage: the outputs " + join(dependent) +
                   " depend on estimated parameters, so the coordinates cannot be read from them");
  Eigen::MatrixXd Cd(static_cast<Eigen::Index>(c.outputs.size()), n);
  for (std::size_t i = 0; i < c.outputs.size(); ++i) Cd.row(static_cast<Eigen::Index>(i)) = m.Cd.row(c.outputs[i]);
  // Which coordinates the measured displacements determine: those in the row space of their output matrix.
  std::vector<std::string> missing;
  if (Cd.rows() == 0) {
    missing = info.coordinates;
  } else {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Cd, Eigen::ComputeFullV);
    const Eigen::Index rank = (svd.singularValues().array() > 1e-10 * svd.singularValues()[0]).count();
    const Eigen::MatrixXd V = svd.matrixV().leftCols(rank);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, i);
      if ((e - V * (V.transpose() * e)).norm() > 1e-8) missing.push_back(info.coordinates[static_cast<std::size_t>(i)]);
    }
  }
  if (!missing.empty()) {
    std::vector<std::string> used;
    for (int o : c.outputs) used.push_back(info.outputs[static_cast<std::size_t>(o)]);
    throw FitError(t.file + ": error: --method arx-two-stage needs every coordinate measured as a displacement; " +
                   (used.empty() ? std::string("the record has no displacement output of the model")
                                 : "its displacement outputs (" + join(used) + ")") +
                   " do not determine " + std::to_string(missing.size()) + " of the " + std::to_string(n) +
                   " coordinates: " + join(missing));
  }
  c.G = Cd.completeOrthogonalDecomposition().pseudoInverse();
  return c;
}

double rms(const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / double(std::max<Eigen::Index>(v.size(), 1))); }

// Least squares X = argmin |A X - B| with A's columns scaled to unit RMS first (coordinates, velocities and forces
// differ by orders of magnitude).
Eigen::MatrixXd scaled_least_squares(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  Eigen::VectorXd s(A.cols());
  for (Eigen::Index j = 0; j < A.cols(); ++j) s[j] = rms(A.col(j)) > 0 ? 1 / rms(A.col(j)) : 1.0;
  const Eigen::MatrixXd X = (A * s.asDiagonal()).colPivHouseholderQr().solve(B);
  return s.asDiagonal() * X;
}

nlohmann::json matrix_json(const Eigen::MatrixXd& X) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < X.cols(); ++j) row.push_back(X(i, j));
    rows.push_back(row);
  }
  return rows;
}


// What stays fixed during one run: the setup, the model at the records' `# set` values and its matrices there.
struct ArxContext {
  const Model& model;
  const ModelInfo& info;
  const std::vector<DataSet>& data;
  MethodSetup setup;
  Eigen::VectorXd base;  // the prior with the records' `# set` values over it
  ModelMatrices m;
  ModelDerivatives d;
  Eigen::Index n = 0, ni = 0, L = 0;  // coordinates, inputs, lags
};

// Setup: the records checked (one `# set` for all: one ARX model), the model evaluated at them, and the mass
// matrix checked known, since the free response determines only M^-1 C and M^-1 K.
ArxContext checked_setup(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                         const ArxTwoStageOptions& arx) {
  ArxContext ctx{model, model.info(), data, methods::method_setup(model, data, options, kMethod), {}, {}, {}};
  if (arx.lags < 2 || arx.lags > 8 || arx.free_response_samples < 20)
    throw FitError("fit: --method arx-two-stage: lags must be 2 to 8 and the free response at least 20 samples");
  const ModelInfo& info = ctx.info;
  ctx.n = static_cast<Eigen::Index>(info.coordinates.size());
  ctx.ni = static_cast<Eigen::Index>(info.inputs.size());
  ctx.L = arx.lags;
  auto same_sets = [](const SetMap& a, const SetMap& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const auto& x, const auto& y) {
             return x.first == y.first && x.second.value == y.second.value;
           });
  };
  for (const DataSet& d : data)
    if (!same_sets(d.set(), data.front().set()))
      throw FitError(d.file() + ": error: --method arx-two-stage fits one ARX model to all records, so they must "
                     "share their `# set` values (this one differs from " + data.front().file() + ")");
  ctx.base = methods::values_for(model, data.front(), ctx.setup.prior);
  model.evaluate(ctx.base, ctx.m);
  model.derivatives(ctx.base, ctx.d);
  std::set<std::string> in_mass;
  for (const DerivativeEntry& e : ctx.d.M)
    if (std::find(ctx.setup.candidates.begin(), ctx.setup.candidates.end(), e.param) != ctx.setup.candidates.end() &&
        e.value != 0)
      in_mass.insert(info.parameters[static_cast<std::size_t>(e.param)].name);
  if (!in_mass.empty())
    throw FitError("fit: --method arx-two-stage needs the mass matrix known (C = -M F1, K = -M F2; the free response "
                   "determines only M^-1 C and M^-1 K): the estimated parameters " +
                   join(std::vector<std::string>(in_mass.begin(), in_mass.end())) +
                   " enter M; make them known with their values (--fix NAME=VALUE)");
  return ctx;
}

// Stage 1's outcome: the coordinates of every record, the regression's target and residual, and the AR blocks.
struct ArxRegression {
  std::vector<Eigen::MatrixXd> qs;  // per record: samples x coordinates
  Eigen::Index rows = 0;            // regression rows over all records
  double dt = 0;
  Eigen::MatrixXd target, residual;
  std::vector<Eigen::MatrixXd> A;  // A_i = coefficient block of q_{t-i}
};

// Stage 1: q_t = sum_{i=1..L} A_i q_{t-i} + sum_{i=0..L} E_i u_{t-i}, all records in one regression (the paper's
// Adaline units reach this least-squares solution).
ArxRegression regress_coordinates(const ArxContext& ctx) {
  const ModelInfo& info = ctx.info;
  const Eigen::Index n = ctx.n, ni = ctx.ni, L = ctx.L;
  const Eigen::Index cols = n * L + ni * (L + 1);
  ArxRegression g;
  for (const DataSet& ds : ctx.data) {
    const TimeRecord& t = std::get<TimeRecord>(ds.content);
    require_inputs(t, info.inputs);
    const Coordinates c = coordinates_from(ctx.model, ctx.setup, ctx.m, ctx.d, t);
    Eigen::MatrixXd y(t.samples(), static_cast<Eigen::Index>(c.outputs.size()));
    for (std::size_t o = 0; o < c.outputs.size(); ++o)
      y.col(static_cast<Eigen::Index>(o)) = t.at(info.outputs[static_cast<std::size_t>(c.outputs[o])]).values;
    g.qs.push_back(y * c.G.transpose());
    if (g.dt == 0) g.dt = t.dt();
    if (std::abs(t.dt() / g.dt - 1) > 1e-6)
      throw FitError(ds.file() + ": error: --method arx-two-stage fits one ARX model to all records, so they must "
                     "share their sampling interval");
    if (t.samples() <= L + cols)
      throw FitError(ds.file() + ": error: --method arx-two-stage: the record is too short for the regression (" +
                     std::to_string(cols) + " coefficients per coordinate)");
    g.rows += t.samples() - L;
  }
  Eigen::MatrixXd Phi(g.rows, cols);
  g.target.resize(g.rows, n);
  Eigen::Index row = 0;
  for (std::size_t r = 0; r < ctx.data.size(); ++r) {
    const TimeRecord& t = std::get<TimeRecord>(ctx.data[r].content);
    const Eigen::MatrixXd& q = g.qs[r];
    for (Eigen::Index k = L; k < t.samples(); ++k, ++row) {
      for (Eigen::Index i = 1; i <= L; ++i) Phi.block(row, (i - 1) * n, 1, n) = q.row(k - i);
      for (Eigen::Index i = 0; i <= L; ++i)
        for (Eigen::Index j = 0; j < ni; ++j) Phi(row, n * L + i * ni + j) = t.at(info.inputs[static_cast<std::size_t>(j)]).values[k - i];
      g.target.row(row) = q.row(k);
    }
  }
  const Eigen::MatrixXd theta = scaled_least_squares(Phi, g.target);  // cols x n
  g.residual = g.target - Phi * theta;
  for (Eigen::Index i = 1; i <= L; ++i) g.A.push_back(theta.block((i - 1) * n, 0, n, n).transpose());
  return g;
}

// Stage 2's outcome: F's upper block row (q'' = F1 q' + F2 q) and the damping and stiffness matrices it gives.
struct IdentifiedMatrices {
  Eigen::MatrixXd Ftop, C, K;
};

// Stage 2: free responses of the AR part from each coordinate displaced and from each given a velocity, sized like
// the measured motion; velocities and accelerations by 4th-order central differences; F from them by least squares,
// and C = -M F1, K = -M F2 with M known.
IdentifiedMatrices identify_matrices(const ArxContext& ctx, const ArxRegression& g, Eigen::Index P) {
  const Eigen::Index n = ctx.n, L = ctx.L;
  const double dt = g.dt;
  Eigen::VectorXd q_scale(n), v_scale(n);
  {
    Eigen::MatrixXd all(g.rows + static_cast<Eigen::Index>(ctx.data.size()) * L, n);
    Eigen::Index at = 0;
    for (const auto& q : g.qs) {
      all.middleRows(at, q.rows()) = q;
      at += q.rows();
    }
    for (Eigen::Index j = 0; j < n; ++j) {
      q_scale[j] = std::max(rms(all.col(j)), 1e-300);
      const Eigen::VectorXd diff = (all.col(j).tail(all.rows() - 1) - all.col(j).head(all.rows() - 1)) / dt;
      v_scale[j] = std::max(rms(diff), 1e-300);
    }
  }
  std::vector<Eigen::VectorXd> z_rows, a_rows;
  for (Eigen::Index j = 0; j < n; ++j)
    for (int kind = 0; kind < 2; ++kind) {
      Eigen::MatrixXd q = Eigen::MatrixXd::Zero(P + L, n);  // q.row(L - 1) is t = 0
      for (Eigen::Index i = 0; i < L; ++i)
        q(L - 1 - i, j) = kind == 0 ? q_scale[j] : -double(i) * dt * v_scale[j];
      for (Eigen::Index t = L; t < P + L; ++t)
        for (Eigen::Index i = 1; i <= L; ++i) q.row(t) += (g.A[static_cast<std::size_t>(i - 1)] * q.row(t - i).transpose()).transpose();
      for (Eigen::Index t = L + 1; t + 2 < P + L; ++t) {
        const Eigen::VectorXd v = (-q.row(t + 2) + 8 * q.row(t + 1) - 8 * q.row(t - 1) + q.row(t - 2)).transpose() / (12 * dt);
        const Eigen::VectorXd a =
            (-q.row(t + 2) + 16 * q.row(t + 1) - 30 * q.row(t) + 16 * q.row(t - 1) - q.row(t - 2)).transpose() / (12 * dt * dt);
        Eigen::VectorXd z(2 * n);
        z << v, q.row(t).transpose();
        // Each instant weighted by the size of its state (in the measured motion's units), so that decaying or
        // growing responses count alike: z' = F z holds instant by instant, at any scale.
        Eigen::VectorXd zs(2 * n);
        zs << v.cwiseQuotient(v_scale), q.row(t).transpose().cwiseQuotient(q_scale);
        const double w = zs.norm() > 0 ? 1 / zs.norm() : 0.0;
        z_rows.push_back(w * z);
        a_rows.push_back(w * a);
      }
    }
  Eigen::MatrixXd Zt(static_cast<Eigen::Index>(z_rows.size()), 2 * n), At(Zt.rows(), n);
  for (std::size_t i = 0; i < z_rows.size(); ++i) {
    Zt.row(static_cast<Eigen::Index>(i)) = z_rows[i].transpose();
    At.row(static_cast<Eigen::Index>(i)) = a_rows[i].transpose();
  }
  // F^T = (Z^T)^+ Z'^T: only F's upper block row is unknown (its lower one is [I 0]), q'' = F1 q' + F2 q.
  IdentifiedMatrices id;
  id.Ftop = scaled_least_squares(Zt, At).transpose();  // n x 2n
  id.C = -ctx.m.M * id.Ftop.leftCols(n);
  id.K = -ctx.m.M * id.Ftop.rightCols(n);
  return id;
}

// Stage 3's outcome: the estimate and what the matrices say of each candidate.
struct MatrixMatch {
  Eigen::VectorXd values;
  estimation::LmResult lm;
  std::vector<int> fitted;                               // model indices the matrices determine
  std::vector<bool> identifiable;                        // per candidate
  std::vector<std::vector<std::string>> confounded;      // per candidate
  std::map<int, std::string> at_bound;                   // model index -> "lower" / "upper"
};

// Stage 3 (ours): the estimated parameters whose K(p), C(p) reproduce the identified matrices, each matrix relative
// to its norm, by least squares over the model's parameterisation. What K and C cannot determine (a parameter in
// neither, or only in a combination) stays at its prior.
MatrixMatch match_parameters(const ArxContext& ctx, const IdentifiedMatrices& id) {
  const Model& model = ctx.model;
  const ModelInfo& info = ctx.info;
  const MethodSetup& setup = ctx.setup;
  const Eigen::VectorXd& base = ctx.base;
  const Eigen::Index n = ctx.n;
  const Eigen::MatrixXd &K_id = id.K, &C_id = id.C;
  const double k_norm = std::max(K_id.norm(), 1e-300), c_norm = std::max(C_id.norm(), 1e-300);
  const std::vector<int>& free = setup.candidates;
  auto residual = [&](const std::vector<int>& params, const Eigen::VectorXd& th, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    Eigen::VectorXd p = base;
    for (std::size_t j = 0; j < params.size(); ++j)
      p[params[j]] = setup.transforms[static_cast<std::size_t>(params[j])].to_physical(th[static_cast<Eigen::Index>(j)]);
    ModelMatrices mp;
    model.evaluate(p, mp);
    r.resize(2 * n * n);
    r.head(n * n) = Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(mp.K - K_id).data(), n * n) / k_norm;
    r.tail(n * n) = Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(mp.C - C_id).data(), n * n) / c_norm;
    if (J) {
      ModelDerivatives dp;
      model.derivatives(p, dp);
      J->setZero(2 * n * n, static_cast<Eigen::Index>(params.size()));
      for (std::size_t j = 0; j < params.size(); ++j) {
        const double g = setup.transforms[static_cast<std::size_t>(params[j])].derivative(th[static_cast<Eigen::Index>(j)]);
        for (const DerivativeEntry& e : dp.K)
          if (e.param == params[j]) (*J)(e.col * n + e.row, static_cast<Eigen::Index>(j)) += e.value * g / k_norm;
        for (const DerivativeEntry& e : dp.C)
          if (e.param == params[j]) (*J)(n * n + e.col * n + e.row, static_cast<Eigen::Index>(j)) += e.value * g / c_norm;
      }
    }
    return r.allFinite();
  };
  auto internal = [&](const std::vector<int>& params, const Eigen::VectorXd& p) {
    Eigen::VectorXd th(static_cast<Eigen::Index>(params.size()));
    for (std::size_t j = 0; j < params.size(); ++j)
      th[static_cast<Eigen::Index>(j)] = setup.transforms[static_cast<std::size_t>(params[j])].to_internal(p[params[j]]);
    return th;
  };
  MatrixMatch mm;
  mm.identifiable.assign(setup.candidates.size(), true);
  mm.confounded.resize(setup.candidates.size());
  {
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    const Eigen::VectorXd th0 = internal(free, base);
    residual(free, th0, r, &J);
    for (std::size_t j = 0; j < free.size(); ++j) {  // relative sensitivities: columns times |p| / (dp/dtheta)
      const ParameterTransform& t = setup.transforms[static_cast<std::size_t>(free[j])];
      const double size = base[free[j]] != 0 ? std::abs(base[free[j]]) : t.scale;
      J.col(static_cast<Eigen::Index>(j)) *= size / t.derivative(th0[static_cast<Eigen::Index>(j)]);
    }
    const IdentifiabilityAnalysis a = analyse_identifiability(J);
    for (std::size_t j = 0; j < free.size(); ++j) {
      mm.identifiable[j] = a.identifiable[j];
      for (int o : a.confounded_with[j]) mm.confounded[j].push_back(info.parameters[static_cast<std::size_t>(free[static_cast<std::size_t>(o)])].name);
    }
  }
  for (std::size_t j = 0; j < free.size(); ++j)
    if (mm.identifiable[j]) mm.fitted.push_back(free[j]);
  mm.values = base;
  if (!mm.fitted.empty()) {
    mm.lm = estimation::levenberg_marquardt(
        [&](const Eigen::VectorXd& th, Eigen::VectorXd& r, Eigen::MatrixXd* J) { return residual(mm.fitted, th, r, J); },
        internal(mm.fitted, base), estimation::LmOptions{});
    for (std::size_t j = 0; j < mm.fitted.size(); ++j)
      mm.values[mm.fitted[j]] = setup.transforms[static_cast<std::size_t>(mm.fitted[j])].to_physical(mm.lm.x[static_cast<Eigen::Index>(j)]);
  }
  for (const auto& [name, v] : ctx.data.front().set())
    mm.values[info.parameter_index(name)] = setup.prior[info.parameter_index(name)];
  // A parameter the matrix fit drove onto a bound (e.g. a damping pushed to its upper bound by a biased C): reported
  // there, not identifiable (parameterization.hpp; no std to compare the distance with, so any within tolerance).
  for (int i : mm.fitted) {
    const ParameterTransform& t = setup.transforms[static_cast<std::size_t>(i)];
    const std::string side = bound_reached(t, mm.values[i], std::numeric_limits<double>::infinity());
    if (side.empty()) continue;
    mm.at_bound[i] = side;
    mm.values[i] = side == "lower" ? t.lower : t.upper;
  }
  return mm;
}

// Finish: each candidate's verdicts from the matrix fit, and no covariance (the method's error is a bias that grows
// with the output noise; no variance of it is honest); scored with the default weighting (records: it does not
// apply) and tolerances.
FitResult finish(const ArxContext& ctx, const MatrixMatch& mm) {
  methods::MethodOutcome outcome;
  outcome.method = kMethod;
  outcome.prior = ctx.setup.prior;
  outcome.values = mm.values;
  for (std::size_t j = 0; j < ctx.setup.candidates.size(); ++j) {
    methods::ReportedParameter p = methods::estimated_parameter(ctx.setup.candidates[j]);
    ParameterEstimate& e = p.verdicts;
    const auto bound = mm.at_bound.find(p.index);
    e.identifiable = mm.identifiable[j] && bound == mm.at_bound.end();
    if (bound != mm.at_bound.end()) e.at_bound = bound->second;
    e.confounded_with = mm.confounded[j];
    e.std = std::numeric_limits<double>::quiet_NaN();
    if (e.identifiable) outcome.estimated.push_back(ctx.info.parameters[static_cast<std::size_t>(p.index)].name);
    outcome.parameters.push_back(p);
  }
  const auto k = static_cast<Eigen::Index>(outcome.estimated.size());
  outcome.covariance = Eigen::MatrixXd::Constant(k, k, std::numeric_limits<double>::quiet_NaN());
  outcome.scored = ctx.setup.candidates;
  outcome.fitted = static_cast<int>(ctx.setup.candidates.size());
  FitResult result;
  methods::finish_result(ctx.model, ctx.data, FitOptions{}, outcome, result);
  result.iterations = mm.lm.iterations;
  result.converged = mm.fitted.empty() || mm.lm.converged;
  result.stop_reason = mm.fitted.empty() ? "nothing to fit" : mm.lm.stop_reason;
  result.cost_history = mm.lm.history;
  return result;
}

// method_details.arx_two_stage: the ARX fit's residual, the identified matrices, and the modes of F (frequencies and
// damping ratios of the identified system) beside the paper's modal damping ratios (its Eqs. 21-22).
nlohmann::json arx_details(const ArxContext& ctx, const ArxRegression& g, const IdentifiedMatrices& id,
                           const MatrixMatch& mm, Eigen::Index P) {
  const ModelInfo& info = ctx.info;
  const Eigen::Index n = ctx.n;
  nlohmann::json j;
  j["lags"] = ctx.L;
  j["free_response_samples"] = P;
  nlohmann::json fit_residual = nlohmann::json::object();
  for (Eigen::Index c = 0; c < n; ++c)
    fit_residual[info.coordinates[static_cast<std::size_t>(c)]] = rms(g.residual.col(c)) / std::max(rms(g.target.col(c)), 1e-300);
  j["arx_relative_residual"] = fit_residual;  // per coordinate: RMS of the one-step residual over RMS of q
  j["coordinates"] = info.coordinates;
  j["K"] = matrix_json(id.K);
  j["C"] = matrix_json(id.C);
  j["M"] = matrix_json(ctx.m.M);
  j["matrix_fit_relative_residual"] = mm.lm.history.empty() ? 0.0 : std::sqrt(mm.lm.cost / 2);
  // Modes of F (z = [q'; q]): frequencies and damping ratios of the identified system.
  Eigen::MatrixXd Fm = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  Fm.topRows(n) = id.Ftop;
  Fm.block(n, 0, n, n).setIdentity();
  nlohmann::json modes = nlohmann::json::array();
  const auto eig = numerics::state_eigen(Fm, numerics::EigenVectors::none);
  std::vector<std::complex<double>> poles;
  for (Eigen::Index i = 0; eig && i < 2 * n; ++i)
    if (eig->lambda[i].imag() > 0) poles.push_back(eig->lambda[i]);
  std::sort(poles.begin(), poles.end(), [](auto a, auto b) { return std::abs(a) < std::abs(b); });
  // The paper's modal damping ratios (its Eqs. 21-22): the undamped modes of M and K, mass-normalised,
  // Gamma = Phi^T C Phi, zeta_i = Gamma_ii / (2 omega_i).
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ge(0.5 * (id.K + id.K.transpose()), ctx.m.M);
  for (Eigen::Index i = 0; i < n; ++i) {
    nlohmann::json mode;
    const double w2 = ge.eigenvalues()[i];
    const Eigen::VectorXd phi = ge.eigenvectors().col(i);
    mode["f_undamped_hz"] = w2 > 0 ? std::sqrt(w2) / numerics::kTwoPi : 0.0;
    mode["zeta_modal"] = w2 > 0 ? phi.dot(id.C * phi) / (2 * std::sqrt(w2)) : std::numeric_limits<double>::quiet_NaN();
    if (static_cast<std::size_t>(i) < poles.size()) {
      mode["f_hz"] = std::abs(poles[static_cast<std::size_t>(i)]) / numerics::kTwoPi;
      mode["zeta"] = -poles[static_cast<std::size_t>(i)].real() / std::abs(poles[static_cast<std::size_t>(i)]);
    }
    modes.push_back(mode);
  }
  j["modes"] = modes;
  return j;
}

}  // namespace

// checked_setup -> regress_coordinates -> identify_matrices -> match_parameters -> finish (+ arx_details)
FitResult fit_arx_two_stage(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                            const ArxTwoStageOptions& arx) {
  const ArxContext ctx = checked_setup(model, data, options, arx);
  const ArxRegression regression = regress_coordinates(ctx);
  const IdentifiedMatrices matrices = identify_matrices(ctx, regression, arx.free_response_samples);
  const MatrixMatch match = match_parameters(ctx, matrices);
  FitResult result = finish(ctx, match);
  result.method_details["arx_two_stage"] = arx_details(ctx, regression, matrices, match, arx.free_response_samples).dump();
  return result;
}

}  // namespace mbgen
