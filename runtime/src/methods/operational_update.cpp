// update_from_operational_modes (mbgen/methods/operational_update.hpp): the modal method's log-scale solver on the
// weighted residuals of output-only modes, with the common-factor ambiguity of unscaled shapes refused.
#include "mbgen/methods/operational_update.hpp"

#include "estimation/fit_inputs.hpp"
#include "modal_solve.hpp"

#include "mbgen/estimation/identifiability.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <limits>
#include <stdexcept>

#include "text/string_format.hpp"

namespace mbgen {

namespace {

constexpr int kDampingIterations = 4;  // the modal method's relinearisations
constexpr int kAlternations = 3;       // rounds of masses/stiffnesses, then dampings
// The residuals' derivative along the common factor of M, C and K (a unit vector of log parameters) below this
// times the largest column: the residuals do not see it (a finite difference along an exact invariance is ~1e-8 of
// a column; on mdof2 a direction that leaves the dampings out is 1e-3, and one that leaves a mass out 0.4).
constexpr double kCommonFactorTolerance = 1e-5;
constexpr double kRankTolerance = 1e-7;  // identifiability's singular-value ratio
// A column below this times the largest is zero: the finite differences through the eigensolver leave ~1e-6 of the
// largest column in parameters the modes do not depend on (the spindle's y stiffnesses under x sensors).
constexpr double kZeroColumn = 1e-5;

std::string names_of(const ModelInfo& info, const std::vector<int>& which) {
  std::string s;
  for (int i : which) s += (s.empty() ? "" : ", ") + info.parameters[static_cast<std::size_t>(i)].name;
  return s;
}

std::string hz_text(const std::vector<OperationalTarget>& targets) {
  std::string s;
  for (const OperationalTarget& t : targets) s += detail::format("%s%.4g Hz", s.empty() ? "" : ", ", t.f_hz);
  return s;
}

// The targets' model modes at p (paired by MAC), or false where the model cannot be evaluated or lacks modes.
struct Paired {
  OperationalModelModes modes;
  std::vector<int> model_mode;
  std::vector<double> mac;
};
bool paired_at(const Model& model, const std::vector<int>& outputs, const std::vector<OperationalTarget>& targets,
               const Eigen::VectorXd& p, Paired& out) {
  try {
    out.modes = operational_model_modes(model, p, outputs);
  } catch (const std::runtime_error&) {  // a singular mass matrix at a trial point
    return false;
  }
  out.model_mode = pair_by_mac(targets, out.modes, &out.mac);
  for (int m : out.model_mode)
    if (m < 0) return false;
  return true;
}

// Refuses mass/stiffness parameters the residuals cannot determine, naming the fix. `common` is the residuals'
// derivative along the common factor (every estimated mass/stiffness and every damping parameter times one factor,
// per unit of its log): zero when nothing known ties the masses and stiffnesses to a scale.
void check_identifiable(const ModelInfo& info, const std::vector<int>& structural, const Eigen::MatrixXd& J,
                        const Eigen::VectorXd& common) {
  Eigen::VectorXd norms(J.cols());
  for (Eigen::Index j = 0; j < J.cols(); ++j) norms[j] = J.col(j).norm();
  const double largest = norms.size() ? norms.maxCoeff() : 0;
  const double per_parameter = common.norm() / std::sqrt(static_cast<double>(J.cols()));
  if (J.cols() > 1 && largest > 0 && per_parameter <= kCommonFactorTolerance * largest)
    throw FitError("modal --update: frequencies and unscaled shapes determine masses and stiffnesses only up "
                   "to a common factor (output-only shapes have no modal mass), and all of " +
                   names_of(info, structural) +
                   " are estimated: make one mass or stiffness known with --fix NAME[=VALUE]");
  IdentifiabilityOptions io;
  io.rank_tolerance = kRankTolerance;
  io.zero_tolerance = kZeroColumn;
  const IdentifiabilityAnalysis a = analyse_identifiability(J, io);
  std::string lost;
  for (std::size_t j = 0; j < structural.size(); ++j) {
    if (a.identifiable[j]) continue;
    std::vector<int> with;
    for (int k : a.confounded_with[j]) with.push_back(structural[static_cast<std::size_t>(k)]);
    lost += (lost.empty() ? "" : "; ") + info.parameters[static_cast<std::size_t>(structural[j])].name +
            (with.empty() ? " (the modes do not depend on it)" : " (confounded with " + names_of(info, with) + ")");
  }
  if (!lost.empty())
    throw FitError("modal --update: the identified modes cannot determine " + lost + " (rank " +
                   std::to_string(a.rank()) + " of " + std::to_string(structural.size()) +
                   "): make " + (lost.find(';') == std::string::npos ? "it" : "each") +
                   " known with --fix NAME[=VALUE]");
}

}  // namespace

OperationalUpdate update_from_operational_modes(const Model& model, const std::vector<std::string>& channels,
                                                const std::vector<OperationalTarget>& all_targets,
                                                const FitOptions& options) {
  const ModelInfo& info = model.info();
  const std::vector<int> outputs = model_outputs_of(info, channels);
  Eigen::VectorXd prior = info.default_values();
  for (const auto& [name, v] : options.values) prior[info.parameter_index(name)] = v;
  const std::vector<int> candidates = estimation::candidate_parameters(info, options);
  const methods::ParameterClasses classes = methods::classify_parameters(model, prior, candidates);
  if (!classes.other.empty()) {
    std::string why = classes.other.front().second;
    const std::string from = "fit: error: --method modal";
    if (why.rfind(from, 0) == 0) why = "modal --update" + why.substr(from.size());
    throw FitError(why + " (make it known with --fix " +
                   info.parameters[static_cast<std::size_t>(classes.other.front().first)].name + ")");
  }
  if (classes.structural.empty())
    throw FitError("modal --update: no mass or stiffness parameter is estimated");

  OperationalUpdate out;
  std::vector<OperationalTarget> targets;
  std::vector<int> target_mode;  // index into all_targets
  for (std::size_t t = 0; t < all_targets.size(); ++t) {
    const OperationalTarget& g = all_targets[t];
    if (std::isfinite(g.f_std_hz) && g.f_std_hz > 0 && std::isfinite(g.shape_std) && g.shape_std > 0) {
      targets.push_back(g);
      target_mode.push_back(static_cast<int>(t));
    } else {
      out.unpaired.push_back(static_cast<int>(t));
      out.notes.push_back(detail::format("the mode at %.4g Hz has no uncertainty (found in too few data blocks): "
                                         "left out of the update", g.f_hz));
    }
  }
  // Where the model has fewer oscillating modes than the data, the data's modes of the lowest MAC are left out.
  Paired before;
  if (targets.empty() || !paired_at(model, outputs, targets, prior, before)) {
    OperationalModelModes mm;
    try {
      mm = operational_model_modes(model, prior, outputs);
    } catch (const std::runtime_error& e) {
      throw FitError(std::string("modal --update: the model cannot be evaluated at its values: ") + e.what());
    }
    const std::vector<int> pairing = pair_by_mac(targets, mm);
    std::vector<OperationalTarget> kept;
    std::vector<int> kept_mode;
    for (std::size_t t = 0; t < targets.size(); ++t) {
      if (pairing[t] >= 0) {
        kept.push_back(targets[t]);
        kept_mode.push_back(target_mode[t]);
      } else {
        out.unpaired.push_back(target_mode[t]);
        out.notes.push_back(detail::format("the mode at %.4g Hz pairs with no model mode (the model has %zu "
                                           "oscillating modes): left out of the update",
                                           targets[t].f_hz, mm.f_hz.size()));
      }
    }
    targets = std::move(kept);
    target_mode = std::move(kept_mode);
    if (targets.empty() || !paired_at(model, outputs, targets, prior, before))
      throw FitError("modal --update: no identified mode with an uncertainty can be paired with the model's");
  }
  std::sort(out.unpaired.begin(), out.unpaired.end());

  const auto per = static_cast<Eigen::Index>(operational_residuals_per_mode(static_cast<int>(channels.size())));
  const methods::ParameterObjectives objectives = [&](const Eigen::VectorXd& p, Eigen::VectorXd& r) {
    Paired at;
    if (!paired_at(model, outputs, targets, p, at)) return false;
    r.resize(per * static_cast<Eigen::Index>(targets.size()));
    for (std::size_t t = 0; t < targets.size(); ++t) {
      const auto m = static_cast<std::size_t>(at.model_mode[t]);
      operational_residuals(targets[t], at.modes.f_hz[m], at.modes.shapes[m],
                            r.segment(per * static_cast<Eigen::Index>(t), per));
    }
    return r.allFinite();
  };
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  if (!methods::log_scale_jacobian(info, objectives, prior, classes.structural, r, J))
    throw FitError("modal --update: the model's modes cannot be paired with the identified ones near its values");
  {
    std::vector<int> every(info.parameters.size());
    std::iota(every.begin(), every.end(), 0);
    const std::vector<int> dampers = methods::classify_parameters(model, prior, every).damping;
    constexpr double h = 1e-6;
    Eigen::VectorXd scaled = prior, r_scaled;
    for (int i : classes.structural) scaled[i] *= std::exp(h);
    for (int i : dampers) scaled[i] *= std::exp(h);
    if (!objectives(scaled, r_scaled))
      throw FitError("modal --update: the model's modes cannot be paired with the identified ones near its values");
    check_identifiable(info, classes.structural, J, (r_scaled - r) / h);
  }
  out.chi2_before = r.squaredNorm();
  out.residuals = static_cast<int>(r.size());

  // The damping ratios, weighted by their standard deviations.
  const auto nt = static_cast<Eigen::Index>(targets.size());
  Eigen::VectorXd zeta_ref(nt), zeta_std(nt);
  for (Eigen::Index t = 0; t < nt; ++t) {
    zeta_ref[t] = targets[static_cast<std::size_t>(t)].zeta;
    zeta_std[t] = targets[static_cast<std::size_t>(t)].zeta_std;
  }
  if (!classes.damping.empty() && !(zeta_std.allFinite() && zeta_std.minCoeff() > 0))
    throw FitError("modal --update: a paired mode's damping ratio has no standard deviation");
  const methods::DampingRatios ratios = [&](const Eigen::VectorXd& q, Eigen::VectorXd& zeta) {
    Paired at;
    if (!paired_at(model, outputs, targets, q, at)) return false;
    zeta.resize(nt);
    for (Eigen::Index t = 0; t < nt; ++t)
      zeta[t] = at.modes.zeta[static_cast<std::size_t>(at.model_mode[static_cast<std::size_t>(t)])];
    return true;
  };

  // Masses and stiffnesses, then dampings, in turn: the shapes of modes with non-proportional damping are complex
  // and depend on the dampings, so masses and stiffnesses fitted at the prior dampings are fitted again.
  Eigen::VectorXd p = prior;
  Eigen::MatrixXd Q;
  const int rounds = classes.damping.empty() ? 1 : kAlternations;
  for (int round = 0; round < rounds; ++round) {
    const methods::LocalOptimum o = methods::log_scale_fit(info, objectives, p, p, classes.structural, options);
    p = o.p;
    out.iterations += o.iterations;
    out.converged = o.converged;
    if (classes.damping.empty()) continue;
    nlohmann::json log = nlohmann::json::array();
    try {
      methods::solve_damping_ratios(info, ratios, zeta_ref, zeta_std, classes.damping, prior, kDampingIterations,
                                    "modal --update", hz_text(targets), p, log, &Q);
    } catch (const FitError& e) {
      throw FitError(std::string(e.what()) + ": make some of " + names_of(info, classes.damping) +
                     " known with --fix NAME[=VALUE]");
    }
  }
  if (!methods::log_scale_jacobian(info, objectives, p, classes.structural, r, J))
    throw FitError("modal --update: the model's modes cannot be paired with the identified ones at the estimate");
  out.chi2_after = r.squaredNorm();
  // Gauss-Newton covariances, the weights being standard deviations: (J^T J)^-1 of log p, not rescaled; the
  // dampings' (Q^T Q)^-1 at the fitted masses and stiffnesses.
  const auto std_of = [](const Eigen::MatrixXd& jacobian) {
    const Eigen::MatrixXd information = jacobian.transpose() * jacobian;
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(information);
    Eigen::VectorXd s = Eigen::VectorXd::Constant(information.cols(), std::numeric_limits<double>::quiet_NaN());
    if (qr.rank() == information.cols()) s = qr.inverse().diagonal().cwiseSqrt();
    return s;
  };
  Eigen::VectorXd structural_std = std_of(J);
  for (Eigen::Index j = 0; j < structural_std.size(); ++j)
    structural_std[j] *= p[classes.structural[static_cast<std::size_t>(j)]];
  const Eigen::VectorXd damping_std = classes.damping.empty() ? Eigen::VectorXd() : std_of(Q);

  for (std::size_t i = 0; i < info.parameters.size(); ++i) {
    const auto index = static_cast<int>(i);
    for (std::size_t j = 0; j < classes.structural.size(); ++j)
      if (classes.structural[j] == index)
        out.parameters.push_back({info.parameters[i].name, "mass/stiffness", prior[index], p[index],
                                  structural_std[static_cast<Eigen::Index>(j)]});
    for (std::size_t j = 0; j < classes.damping.size(); ++j)
      if (classes.damping[j] == index)
        out.parameters.push_back({info.parameters[i].name, "damping", prior[index], p[index],
                                  damping_std[static_cast<Eigen::Index>(j)]});
  }
  Paired after;
  if (!paired_at(model, outputs, targets, p, after))
    throw FitError("modal --update: the model's modes cannot be paired with the identified ones at the estimate");
  for (std::size_t t = 0; t < targets.size(); ++t) {
    UpdatedPair u;
    const OperationalTarget& g = targets[t];
    u.mode = target_mode[t];
    u.f_hz = g.f_hz;
    u.f_std_hz = g.f_std_hz;
    u.zeta = g.zeta;
    u.zeta_std = g.zeta_std;
    u.shape_std = g.shape_std;
    const auto b = static_cast<std::size_t>(before.model_mode[t]), a = static_cast<std::size_t>(after.model_mode[t]);
    u.model_mode_before = before.model_mode[t];
    u.model_f_before = before.modes.f_hz[b];
    u.model_zeta_before = before.modes.zeta[b];
    u.mac_before = before.mac[t];
    u.model_mode_after = after.model_mode[t];
    u.model_f_after = after.modes.f_hz[a];
    u.model_zeta_after = after.modes.zeta[a];
    u.mac_after = after.mac[t];
    out.pairs.push_back(u);
  }
  return out;
}

}  // namespace mbgen
