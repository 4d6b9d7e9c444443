#include "mbgen/methods/two_step.hpp"

#include "estimation/fit_setup.hpp"
#include "estimation/multistart.hpp"
#include "estimation/value_checks.hpp"
#include "numerics/levenberg_marquardt.hpp"
#include "analytical_route.hpp"
#include "coefficient_problem.hpp"
#include "method_result.hpp"
#include "model_coefficients.hpp"
#include "step_one.hpp"
#include "validation.hpp"
#include "mbgen/estimation/identifiability.hpp"
#include "mbgen/estimation/parameterization.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

namespace mbgen {

using methods::CoefficientProblem;

namespace {

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

// Pseudo-inverse of a symmetric positive semi-definite matrix (relative cut 1e-14).
Eigen::MatrixXd pinv_spd(const Eigen::MatrixXd& H) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd s = svd.singularValues();
  Eigen::VectorXd inv = Eigen::VectorXd::Zero(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i)
    if (s[i] > s[0] * 1e-14) inv[i] = 1 / s[i];
  return svd.matrixV() * inv.asDiagonal() * svd.matrixU().transpose();
}

// Step two's search in the bounded internal coordinates of parameterization.hpp.
class Search {
 public:
  Search(const CoefficientProblem& problem, const Eigen::VectorXd& prior, const std::vector<ParameterTransform>& t)
      : problem_(problem), prior_(prior), transforms_(t) {}
  Eigen::VectorXd full(const std::vector<int>& free, const Eigen::VectorXd& theta) const {
    return estimation::physical_values(prior_, free, transforms_, theta);
  }
  Eigen::VectorXd internal(const std::vector<int>& free, const Eigen::VectorXd& v) const {
    return estimation::internal_values(free, transforms_, v);
  }
  estimation::ResidualFunction function(const std::vector<int>& free) const {
    return [this, free](const Eigen::VectorXd& theta, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
      try {
        problem_.evaluate(full(free, theta), free, r, J);
      } catch (const std::runtime_error&) {  // a failed trial (DynamicsError); a logic_error is a bug and goes on
        return false;
      }
      if (!r.allFinite() || (J && !J->allFinite())) return false;
      if (J)
        for (std::size_t j = 0; j < free.size(); ++j)
          J->col(static_cast<Eigen::Index>(j)) *=
              transforms_[static_cast<std::size_t>(free[j])].derivative(theta[static_cast<Eigen::Index>(j)]);
      return true;
    };
  }

 private:
  const CoefficientProblem& problem_;
  Eigen::VectorXd prior_;
  std::vector<ParameterTransform> transforms_;
};

struct NewtonSolution {
  Eigen::VectorXd values;
  double residual = 0;  // max |normalised mismatch|
  bool admissible = false;
  int starts = 0;       // how many starts reached it
};

// Damped Newton on the square system L(p) = L^ in physical coordinates (no bounds: a root outside them is reported
// as inadmissible, as the thesis's unconstrained solutions were). Returns the root, or nothing.
std::optional<Eigen::VectorXd> newton(const CoefficientProblem& problem, const std::vector<int>& free, Eigen::VectorXd v,
                                      const Eigen::VectorXd& scale, double* residual) {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  try {
    problem.evaluate(v, free, r, &J);
  } catch (const std::runtime_error&) {  // as in Search::function
    return std::nullopt;
  }
  for (int it = 0; it < 100; ++it) {
    const Eigen::VectorXd step = -(J * scale.asDiagonal()).colPivHouseholderQr().solve(r);
    if (!step.allFinite()) return std::nullopt;
    double alpha = 1;
    bool accepted = false;
    for (int half = 0; half < 40 && !accepted; ++half, alpha /= 2) {
      Eigen::VectorXd trial = v;
      for (std::size_t j = 0; j < free.size(); ++j)
        trial[free[j]] += alpha * scale[static_cast<Eigen::Index>(j)] * step[static_cast<Eigen::Index>(j)];
      Eigen::VectorXd rt;
      Eigen::MatrixXd Jt;
      try {
        problem.evaluate(trial, free, rt, &Jt);
      } catch (const std::runtime_error&) {  // as in Search::function
        continue;
      }
      if (!rt.allFinite() || rt.norm() >= r.norm()) continue;
      v = trial;
      r = rt;
      J = Jt;
      accepted = true;
    }
    if (!accepted || alpha * step.norm() < 1e-13) break;
  }
  *residual = r.cwiseAbs().maxCoeff();
  if (*residual > 1e-6) return std::nullopt;
  return v;
}

}  // namespace

FitResult fit_two_step(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                       const TwoStepOptions& two_step) {
  if (two_step.solver != "auto" && two_step.solver != "minimisation" && two_step.solver != "newton" &&
      two_step.solver != "analytical")
    throw FitError("two-step: unknown solver " + two_step.solver + " (auto, analytical, newton or minimisation)");
  if (two_step.weighting != "normalised" && two_step.weighting != "covariance")
    throw FitError("two-step: unknown weighting " + two_step.weighting + " (normalised or covariance)");
  if (two_step.criterion != "aic" && two_step.criterion != "bic" && two_step.criterion != "fpe")
    throw FitError("two-step: unknown order criterion " + two_step.criterion + " (aic, bic or fpe)");
  if (two_step.model != "armax" && two_step.model != "arx")
    throw FitError("two-step: unknown model " + two_step.model + " for records (armax or arx)");
  if (data.empty()) throw FitError("two-step: no data");
  const ModelInfo& info = model.info();
  const estimation::FitSetup setup = estimation::prepare_fit(model, data, options);
  const Eigen::VectorXd& prior = setup.prior;
  const std::vector<int>& candidates = setup.candidates;
  const std::vector<ParameterTransform>& transforms = setup.transforms;

  // ---- step one ----
  const methods::StepOne one = methods::run_step_one(model, data, prior, candidates, two_step, options.threads);
  CoefficientProblem problem(model, one.tfs);
  const bool whitened = two_step.weighting == "covariance" && problem.use_covariance_weighting();
  if (two_step.weighting == "covariance" && !whitened)
    throw FitError("two-step: covariance weighting needs step one's coefficient covariance, which time records "
                   "(ARX, ARMAX) do not give");
  const Search search(problem, prior, transforms);
  const auto n_eq = static_cast<Eigen::Index>(problem.targets().size());

  FitResult result;
  methods::describe_run(info, data, "two-step", prior, result);

  // Identifiability at the prior, on the coefficient residuals (relative sensitivities).
  IdentifiabilityOptions id_options;
  id_options.zero_tolerance = options.zero_tolerance;
  id_options.rank_tolerance = options.rank_tolerance;
  auto scaled_jacobian = [&](const std::vector<int>& cols, const Eigen::VectorXd& v) {
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    problem.evaluate(v, cols, r, &J);
    for (std::size_t j = 0; j < cols.size(); ++j) {
      const double s = std::abs(v[cols[j]]) > 0 ? std::abs(v[cols[j]]) : transforms[static_cast<std::size_t>(cols[j])].scale;
      J.col(static_cast<Eigen::Index>(j)) *= s;
    }
    return J;
  };
  std::vector<bool> identifiable(candidates.size(), true);
  std::vector<std::vector<int>> confounded(candidates.size());
  std::vector<int> free;
  {
    const IdentifiabilityAnalysis a = analyse_identifiability(scaled_jacobian(candidates, prior), id_options);
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      identifiable[c] = a.identifiable[c];
      for (int o : a.confounded_with[c]) confounded[c].push_back(candidates[static_cast<std::size_t>(o)]);
      if (identifiable[c]) free.push_back(candidates[c]);
    }
  }
  if (free.empty()) throw FitError("two-step: the identified coefficients determine none of the parameters to estimate");
  if (n_eq < static_cast<Eigen::Index>(free.size()))
    throw FitError("two-step: " + std::to_string(n_eq) + " compared coefficients cannot determine " +
                   std::to_string(free.size()) + " parameters (the thesis: add a transfer function or lump parameters)");
  const bool square = n_eq == static_cast<Eigen::Index>(free.size());
  if (two_step.solver == "newton" && !square)
    throw FitError("two-step: the newton solver needs as many compared coefficients as parameters; there are " +
                   std::to_string(n_eq) + " for " + std::to_string(free.size()));

  // Starting points: the prior, then log-uniform within +-log(spread) of it in internal coordinates (as fit()).
  const int starts = std::max(1, options.starts);
  const std::vector<Eigen::VectorXd> start_points =
      estimation::start_points(search.internal(free, prior), free, transforms, options);

  // ---- step two (c): minimisation of Q_TF from every start ----
  estimation::LmOptions lm;
  lm.max_iterations = options.max_iterations;
  lm.cost_tolerance = options.cost_tolerance;
  lm.step_tolerance = options.step_tolerance;
  lm.gradient_tolerance = options.gradient_tolerance;
  const estimation::ResidualFunction f = search.function(free);
  const std::vector<estimation::LmResult> runs = estimation::run_starts(starts, options.threads, [&](int s) {
    return estimation::levenberg_marquardt(f, start_points[static_cast<std::size_t>(s)], lm);
  });
  for (const auto& run : runs) result.start_costs.push_back(run.cost);
  result.best_start = estimation::best_start(runs);
  const estimation::LmResult& best = runs[static_cast<std::size_t>(result.best_start)];
  if (!std::isfinite(best.cost)) throw FitError("two-step: the model cannot be evaluated at any starting point");
  const Eigen::VectorXd minimum = search.full(free, best.x);
  // Starts that reached the same estimate (every parameter within 1e-4 of it, relatively): the repeatability the
  // thesis's Table 5.5 reports.
  int at_best = 0;
  for (const auto& run : runs) {
    if (!std::isfinite(run.cost)) continue;
    const Eigen::VectorXd v = search.full(free, run.x);
    double d = 0;
    for (int i : free) d = std::max(d, std::abs(v[i] - minimum[i]) / std::max(std::abs(minimum[i]), 1e-300));
    if (d < 1e-4) ++at_best;
  }

  // ---- step two (b): Newton on the square system, from the minimum and every start ----
  std::vector<NewtonSolution> roots;
  nlohmann::json newton_json;
  if (square) {
    Eigen::VectorXd scale(static_cast<Eigen::Index>(free.size()));
    for (std::size_t j = 0; j < free.size(); ++j) scale[static_cast<Eigen::Index>(j)] = transforms[static_cast<std::size_t>(free[j])].scale;
    std::vector<Eigen::VectorXd> from = {minimum};
    for (const auto& theta : start_points) from.push_back(search.full(free, theta));
    for (const auto& v0 : from) {
      double residual = 0;
      const std::optional<Eigen::VectorXd> root = newton(problem, free, v0, scale, &residual);
      if (!root) continue;
      bool known = false;
      for (auto& r : roots) {
        double d = 0;
        for (int i : free) d = std::max(d, std::abs(r.values[i] - (*root)[i]) / std::max(std::abs(r.values[i]), 1e-300));
        if (d < 1e-6) {
          ++r.starts;
          known = true;
          break;
        }
      }
      if (!known) roots.push_back({*root, residual, methods::admissible(model, *root, free), 1});
    }
    nlohmann::json sols = nlohmann::json::array();
    for (const auto& r : roots) {
      nlohmann::json vals;
      for (int i : free) vals[info.parameters[static_cast<std::size_t>(i)].name] = number(r.values[i]);
      sols.push_back({{"values", vals}, {"admissible", r.admissible}, {"max_mismatch", number(r.residual)},
                      {"reached_from", r.starts}});
    }
    newton_json = {{"applicable", true}, {"starts", static_cast<int>(from.size())}, {"solutions", sols}};
  } else {
    newton_json = {{"applicable", false},
                   {"reason", std::to_string(n_eq) + " coefficient equations for " + std::to_string(free.size()) +
                                  " parameters: not square; the minimisation is the least-squares solution"}};
  }

  // ---- step two (a): the analytical solution, where a solver is given ----
  // The covariance weighting is a weighted least-squares solution of all the equations; the analytical route solves
  // a square subsystem exactly, where no weight acts, so `auto` leaves it out when the weighting is asked for (it
  // used to take it and say "whitened" while the weights changed nothing).
  methods::AnalyticalOutcome analytical;
  if (whitened && two_step.solver == "analytical")
    throw FitError("two-step: the analytical route solves a square subsystem exactly, where the covariance weighting "
                   "has nothing to weight; use the minimisation route (or auto) with it");
  if (whitened && two_step.solver == "auto") {
    analytical.reason = "not tried: the covariance weighting asks for the weighted least-squares solution";
    analytical.details = {{"available", nullptr}, {"reason", analytical.reason}};
  } else if (two_step.solver == "auto" || two_step.solver == "analytical") {
    analytical = methods::analytical_route(model, one.tfs, free, prior, minimum, two_step.analytical);
    if (!analytical.solved && two_step.solver == "analytical")
      throw FitError("two-step: the analytical route cannot be taken: " + analytical.reason);
  } else {
    analytical.reason = "not tried: route " + std::string(two_step.solver == "newton" ? "numerical" : two_step.solver) + " asked for";
    analytical.details = {{"available", nullptr}, {"reason", analytical.reason}};
  }

  // The estimate (Table 3.2): the analytical solution where there is an admissible one, else Newton's admissible root
  // nearest the minimum where the system is square (the numerical solution before the minimisation), else the
  // minimum.
  Eigen::VectorXd values = minimum;
  std::string solver = "minimisation";
  if (analytical.solved) {
    values = analytical.values;
    solver = "analytical";
  } else if (square && two_step.solver != "minimisation") {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& r : roots) {
      if (!r.admissible) continue;
      double d = 0;
      for (int i : free) d += std::pow(std::log(std::abs(r.values[i]) / std::max(std::abs(minimum[i]), 1e-300)), 2);
      if (d < nearest) {
        nearest = d;
        values = r.values;
        solver = "newton";
      }
    }
    if (two_step.solver == "newton" && solver != "newton")
      throw FitError("two-step: Newton's method found no admissible root of the coefficient equations from " +
                     std::to_string(starts + 1) + " starts");
  }

  // ---- uncertainty: step one's coefficient covariance through step two's linearisation (sandwich) ----
  Eigen::VectorXd r_est, model_coefficients;
  Eigen::MatrixXd J_est;
  problem.evaluate(values, free, r_est, &J_est, &model_coefficients);
  const Eigen::MatrixXd sigma_hat = problem.identified_covariance();
  Eigen::MatrixXd cov;
  std::string uncertainty_note;
  if (solver == "analytical" && analytical.covariance.size()) {
    cov = analytical.covariance;
    uncertainty_note = "step one's coefficient covariance propagated through the exact solution of the chosen square "
                       "subsystem S: J_S^-1 S_S J_S^-T";
  } else if (sigma_hat.size()) {
    const Eigen::MatrixXd W = problem.weight();
    Eigen::VectorXd sc(static_cast<Eigen::Index>(free.size()));
    for (std::size_t j = 0; j < free.size(); ++j) sc[static_cast<Eigen::Index>(j)] = std::max(std::abs(values[free[j]]), 1e-300);
    const Eigen::MatrixXd Js = J_est * sc.asDiagonal();
    const Eigen::MatrixXd Hi = pinv_spd(Js.transpose() * Js);
    const Eigen::MatrixXd Sw = W * sigma_hat * W.transpose();
    cov = sc.asDiagonal() * (Hi * Js.transpose() * Sw * Js * Hi) * sc.asDiagonal();
    uncertainty_note = "step one's coefficient covariance propagated through step two's linearisation at the estimate: "
                       "(J^T W J)^-1 J^T W S W J (J^T W J)^-1";
  } else {
    uncertainty_note = "std null: " + one.tfs.front().tf.covariance_note;
    for (const auto& s : one.tfs)
      if (s.tf.covariance.size() == 0) uncertainty_note = "std null: " + s.tf.covariance_note;
  }

  // Parameters the minimum pressed against a bound.
  std::map<int, std::string> at_bound;
  for (std::size_t j = 0; j < free.size(); ++j) {
    const int i = free[j];
    const double sd = cov.size() ? std::sqrt(std::max(cov(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j)), 0.0))
                                 : std::numeric_limits<double>::quiet_NaN();
    const std::string side = bound_reached(transforms[static_cast<std::size_t>(i)], values[i], sd);
    if (side.empty()) continue;
    at_bound[i] = side;
    values[i] = side == "lower" ? transforms[static_cast<std::size_t>(i)].lower : transforms[static_cast<std::size_t>(i)].upper;
  }
  std::vector<std::size_t> interior;
  for (std::size_t j = 0; j < free.size(); ++j)
    if (!at_bound.count(free[j])) interior.push_back(j);
  for (std::size_t j : interior) result.estimated.push_back(info.parameters[static_cast<std::size_t>(free[j])].name);
  if (cov.size() && !interior.empty()) {
    result.covariance.resize(static_cast<Eigen::Index>(interior.size()), static_cast<Eigen::Index>(interior.size()));
    for (std::size_t a = 0; a < interior.size(); ++a)
      for (std::size_t b = 0; b < interior.size(); ++b)
        result.covariance(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
            cov(static_cast<Eigen::Index>(interior[a]), static_cast<Eigen::Index>(interior[b]));
    const Eigen::VectorXd sd = result.covariance.diagonal().cwiseMax(0).cwiseSqrt();
    result.correlation = result.covariance.cwiseQuotient(sd * sd.transpose());
  } else if (!interior.empty()) {
    // No covariance (time records): the matrices keep the size of `estimated`, as fit.hpp has them, and say unknown.
    const Eigen::Index k = static_cast<Eigen::Index>(interior.size());
    result.covariance = Eigen::MatrixXd::Constant(k, k, std::numeric_limits<double>::quiet_NaN());
    result.correlation = result.covariance;
  }
  result.values = values;
  result.singular_values = analyse_identifiability(scaled_jacobian(candidates, values), id_options).singular_values;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const int i = candidates[c];
    ParameterEstimate e = methods::parameter_estimate(info, i, prior, values);
    e.estimated = identifiable[c];
    e.identifiable = identifiable[c] && !at_bound.count(i);
    if (at_bound.count(i)) e.at_bound = at_bound[i];
    e.std = std::numeric_limits<double>::quiet_NaN();
    const auto it = std::find(free.begin(), free.end(), i);
    if (it != free.end() && cov.size()) {
      const Eigen::Index j = it - free.begin();
      e.std = std::sqrt(std::max(cov(j, j), 0.0));
    }
    std::vector<int> conf = confounded[c];
    std::sort(conf.begin(), conf.end());
    conf.erase(std::unique(conf.begin(), conf.end()), conf.end());
    for (int o : conf) e.confounded_with.push_back(info.parameters[static_cast<std::size_t>(o)].name);
    result.parameters.push_back(e);
  }

  // The data misfit at the estimate on the output-error scale, and the modes, as every method reports them
  // (method_result.hpp). No candidates: the singular values stay step two's (set above).
  methods::score_by_output_error(model, data, options, {}, static_cast<int>(free.size()), result);
  result.iterations = best.iterations;
  result.converged = best.converged;
  result.stop_reason = best.stop_reason;
  result.cost_history = best.history;

  // ---- method_details ----
  nlohmann::json start_costs = nlohmann::json::array();
  for (double c : result.start_costs) start_costs.push_back(number(c));
  nlohmann::json coefficients = nlohmann::json::array();
  double q_tf = 0;  // the thesis's Eq. 3.99 whatever the weighting
  for (Eigen::Index i = 0; i < n_eq; ++i) {
    const double v = problem.targets()[static_cast<std::size_t>(i)].value;
    q_tf += std::pow((model_coefficients[i] - v) / v, 2);
  }
  for (Eigen::Index i = 0; i < n_eq; ++i) {
    const methods::CoefficientTarget& t = problem.targets()[static_cast<std::size_t>(i)];
    const methods::StepOneTf& s = one.tfs[t.tf];
    coefficients.push_back({{"data", s.file},
                            {"polynomial", t.channel < 0 ? "denominator" : s.tf.outputs[static_cast<std::size_t>(t.channel)] + "/" + s.tf.input},
                            {"power", t.power},
                            {"identified", number(t.value)},
                            {"model", number(model_coefficients[i])},
                            {"relative_mismatch", number((model_coefficients[i] - t.value) / std::abs(t.value))}});
  }
  const std::string route = solver == "newton" ? "numerical" : solver;
  std::string route_reason;
  if (solver == "analytical") {
    route_reason = "the exact solution of " + std::to_string(analytical.equations.size()) + " of the " +
                   std::to_string(n_eq) + " coefficient equations";
  } else {
    route_reason = two_step.solver == "auto" ? "analytical route not taken: " + analytical.reason + "; " : "";
    route_reason += solver == "newton" ? "Newton's admissible root of the square system"
                    : !square         ? "the minimisation (the least-squares solution of the overdetermined system)"
                    : two_step.solver == "minimisation" ? "the minimisation, as asked"
                                                        : "the minimisation (Newton found no admissible root)";
  }
  nlohmann::json step_two = {
      {"route", route},
      {"route_reason", route_reason},
      {"solver", solver},
      {"equations", n_eq},
      {"unknowns", static_cast<int>(free.size())},
      {"weighting", whitened ? "covariance: the normalised mismatches whitened by step one's covariance"
                             : "normalised by the identified coefficient (thesis Eq. 3.98)"},
      {"q_tf", number(q_tf)},
      {"cost", number(r_est.squaredNorm())},
      {"coefficients", coefficients},
      {"minimisation", {{"starts", starts}, {"best_start", result.best_start}, {"starts_at_best", at_best},
                        {"cost", number(best.cost)}, {"start_costs", start_costs}}},
      {"newton", newton_json},
      {"analytical", analytical.details},
      {"uncertainty", uncertainty_note}};
  nlohmann::json zero_pole = nlohmann::json::array(), checks = nlohmann::json::array();
  int suspect = 0;
  for (const methods::StepOneTf& s : one.tfs) {
    Eigen::VectorXd v = values;
    for (const auto& [p, value] : s.overrides) v[p] = value;
    const methods::Validation val = methods::validate(
        s, s.truncated_to.empty() ? methods::model_tf(model, v, s.input, s.outputs, {})
                                  : methods::model_tf_truncated(model, v, s.input, s.outputs, s.truncated_to, {}));
    zero_pole.push_back(val.zero_pole);
    checks.push_back(val.checks);
    suspect += val.suspect_poles;
  }
  nlohmann::json details;
  details["summary"] = "step two by the " + route + " route: " + route_reason +
                       (whitened ? "; residuals whitened by step one's coefficient covariance" : "");
  details["step_one"] = one.details;
  details["step_two"] = step_two;
  details["zero_pole"] = zero_pole;
  details["checks"] = {{"transfer_functions", checks},
                       {"verdict", suspect ? "suspect: " + std::to_string(suspect) + " identified poles fail a check"
                                           : "valid: every identified pole passes the checks"}};
  result.method_details["two_step"] = details.dump();
  return result;
}

}  // namespace mbgen
