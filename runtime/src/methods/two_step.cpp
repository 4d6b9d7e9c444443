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

using estimation::identifiability_options;
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

// The options' names, checked before any work (a library caller may pass any string).
void check_options(const TwoStepOptions& two_step) {
  if (two_step.solver != "auto" && two_step.solver != "minimisation" && two_step.solver != "newton" &&
      two_step.solver != "analytical")
    throw FitError("two-step: unknown solver " + two_step.solver + " (auto, analytical, newton or minimisation)");
  if (two_step.weighting != "normalised" && two_step.weighting != "covariance")
    throw FitError("two-step: unknown weighting " + two_step.weighting + " (normalised or covariance)");
  if (two_step.criterion != "aic" && two_step.criterion != "bic" && two_step.criterion != "fpe")
    throw FitError("two-step: unknown order criterion " + two_step.criterion + " (aic, bic or fpe)");
  if (two_step.model != "armax" && two_step.model != "arx")
    throw FitError("two-step: unknown model " + two_step.model + " for records (armax or arx)");
}

// What stays fixed during one run: output error's setup, step one's transfer functions and step two's problem on
// their coefficients. Not copyable: the problem refers to step one's result, the search to the problem
// (the problem is not const: choosing its weighting sets it up).
struct TwoStepContext {
  TwoStepContext(const Model& m, const std::vector<DataSet>& d, const FitOptions& o, const TwoStepOptions& t)
      : model(m), info(m.info()), data(d), options(o), two_step(t), setup(estimation::prepare_fit(m, d, o)),
        one(methods::run_step_one(m, d, setup.prior, setup.candidates, t, o.threads)), problem(m, one.tfs),
        whitened(t.weighting == "covariance" && problem.use_covariance_weighting()),
        search(problem, setup.prior, setup.transforms), n_eq(static_cast<Eigen::Index>(problem.targets().size())) {}
  TwoStepContext(const TwoStepContext&) = delete;
  TwoStepContext& operator=(const TwoStepContext&) = delete;

  const Model& model;
  const ModelInfo& info;
  const std::vector<DataSet>& data;
  const FitOptions& options;
  const TwoStepOptions& two_step;
  const estimation::FitSetup setup;  // prior, candidates, transforms
  const methods::StepOne one;        // step one: the identified transfer functions
  CoefficientProblem problem;  // step two: the model's coefficients against step one's
  const bool whitened;               // the covariance weighting applies
  const Search search;
  const Eigen::Index n_eq;           // compared coefficients
};

// The coefficient residuals' Jacobian of `cols` at `v`, each column times the parameter's size (relative
// sensitivities, as the identifiability analysis takes them).
Eigen::MatrixXd scaled_jacobian(const TwoStepContext& ctx, const std::vector<int>& cols, const Eigen::VectorXd& v) {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  ctx.problem.evaluate(v, cols, r, &J);
  for (std::size_t j = 0; j < cols.size(); ++j) {
    const double s = std::abs(v[cols[j]]) > 0 ? std::abs(v[cols[j]]) : ctx.setup.transforms[static_cast<std::size_t>(cols[j])].scale;
    J.col(static_cast<Eigen::Index>(j)) *= s;
  }
  return J;
}

// Which candidates the coefficients determine (at the prior), what each is confounded with, and those step two moves.
struct StepTwoUnknowns {
  std::vector<bool> identifiable;            // per candidate
  std::vector<std::vector<int>> confounded;  // per candidate: model indices
  std::vector<int> free;                     // the identifiable candidates
  bool square = false;                       // as many compared coefficients as free parameters
};

// Step two's unknowns: the identifiable candidates, refused when the coefficients cannot determine them (too few
// equations, or none determined) or when the numerical route was asked for a system that is not square.
StepTwoUnknowns unknowns_at_prior(const TwoStepContext& ctx) {
  const std::vector<int>& candidates = ctx.setup.candidates;
  StepTwoUnknowns u;
  u.identifiable.assign(candidates.size(), true);
  u.confounded.resize(candidates.size());
  const IdentifiabilityAnalysis a =
      analyse_identifiability(scaled_jacobian(ctx, candidates, ctx.setup.prior), identifiability_options(ctx.options));
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    u.identifiable[c] = a.identifiable[c];
    for (int o : a.confounded_with[c]) u.confounded[c].push_back(candidates[static_cast<std::size_t>(o)]);
    if (u.identifiable[c]) u.free.push_back(candidates[c]);
  }
  if (u.free.empty()) throw FitError("two-step: the identified coefficients determine none of the parameters to estimate");
  if (ctx.n_eq < static_cast<Eigen::Index>(u.free.size()))
    throw FitError("two-step: " + std::to_string(ctx.n_eq) + " compared coefficients cannot determine " +
                   std::to_string(u.free.size()) + " parameters (the thesis: add a transfer function or lump parameters)");
  u.square = ctx.n_eq == static_cast<Eigen::Index>(u.free.size());
  if (ctx.two_step.solver == "newton" && !u.square)
    throw FitError("two-step: the newton solver needs as many compared coefficients as parameters; there are " +
                   std::to_string(ctx.n_eq) + " for " + std::to_string(u.free.size()));
  return u;
}

// Step two (c)'s outcome: every start's run, the best, and how many starts reached it.
struct Minimisation {
  std::vector<estimation::LmResult> runs;
  int best_start = 0;
  Eigen::VectorXd minimum;  // all model parameters at the best run
  int at_best = 0;
};

// Step two (c): the coefficient mismatch Q_TF minimised from every start (the prior, then log-uniform within
// +-log(spread) of it in internal coordinates, as fit()); the starts that reached the same estimate (every parameter
// within 1e-4 of it, relatively) are the repeatability the thesis's Table 5.5 reports.
Minimisation minimise_mismatch(const TwoStepContext& ctx, const std::vector<int>& free,
                               const std::vector<Eigen::VectorXd>& start_points) {
  estimation::LmOptions lm;
  lm.max_iterations = ctx.options.max_iterations;
  lm.cost_tolerance = ctx.options.cost_tolerance;
  lm.step_tolerance = ctx.options.step_tolerance;
  lm.gradient_tolerance = ctx.options.gradient_tolerance;
  const estimation::ResidualFunction f = ctx.search.function(free);
  Minimisation m;
  m.runs = estimation::run_starts(std::max(1, ctx.options.starts), ctx.options.threads, [&](int s) {
    return estimation::levenberg_marquardt(f, start_points[static_cast<std::size_t>(s)], lm);
  });
  m.best_start = estimation::best_start(m.runs);
  const estimation::LmResult& best = m.runs[static_cast<std::size_t>(m.best_start)];
  if (!std::isfinite(best.cost)) throw FitError("two-step: the model cannot be evaluated at any starting point");
  m.minimum = ctx.search.full(free, best.x);
  for (const auto& run : m.runs) {
    if (!std::isfinite(run.cost)) continue;
    const Eigen::VectorXd v = ctx.search.full(free, run.x);
    double d = 0;
    for (int i : free) d = std::max(d, std::abs(v[i] - m.minimum[i]) / std::max(std::abs(m.minimum[i]), 1e-300));
    if (d < 1e-4) ++m.at_best;
  }
  return m;
}

// Step two (b)'s outcome: the distinct roots and method_details.two_step.step_two.newton.
struct NewtonRoots {
  std::vector<NewtonSolution> roots;
  nlohmann::json details;
};

// Step two (b): Newton on the square system, from the minimum and every start; where the system is not square it
// does not apply (the minimisation is the least-squares solution).
NewtonRoots newton_roots(const TwoStepContext& ctx, const StepTwoUnknowns& u, const Eigen::VectorXd& minimum,
                         const std::vector<Eigen::VectorXd>& start_points) {
  const std::vector<int>& free = u.free;
  NewtonRoots out;
  if (!u.square) {
    out.details = {{"applicable", false},
                   {"reason", std::to_string(ctx.n_eq) + " coefficient equations for " + std::to_string(free.size()) +
                                  " parameters: not square; the minimisation is the least-squares solution"}};
    return out;
  }
  Eigen::VectorXd scale(static_cast<Eigen::Index>(free.size()));
  for (std::size_t j = 0; j < free.size(); ++j)
    scale[static_cast<Eigen::Index>(j)] = ctx.setup.transforms[static_cast<std::size_t>(free[j])].scale;
  std::vector<Eigen::VectorXd> from = {minimum};
  for (const auto& theta : start_points) from.push_back(ctx.search.full(free, theta));
  for (const auto& v0 : from) {
    double residual = 0;
    const std::optional<Eigen::VectorXd> root = newton(ctx.problem, free, v0, scale, &residual);
    if (!root) continue;
    bool known = false;
    for (auto& r : out.roots) {
      double d = 0;
      for (int i : free) d = std::max(d, std::abs(r.values[i] - (*root)[i]) / std::max(std::abs(r.values[i]), 1e-300));
      if (d < 1e-6) {
        ++r.starts;
        known = true;
        break;
      }
    }
    if (!known) out.roots.push_back({*root, residual, methods::admissible(ctx.model, *root, free), 1});
  }
  nlohmann::json sols = nlohmann::json::array();
  for (const auto& r : out.roots) {
    nlohmann::json vals;
    for (int i : free) vals[ctx.info.parameters[static_cast<std::size_t>(i)].name] = number(r.values[i]);
    sols.push_back({{"values", vals}, {"admissible", r.admissible}, {"max_mismatch", number(r.residual)},
                    {"reached_from", r.starts}});
  }
  out.details = {{"applicable", true}, {"starts", static_cast<int>(from.size())}, {"solutions", sols}};
  return out;
}

// Step two (a): the analytical solution, where a solver is given and the route may take it. The covariance
// weighting is a weighted least-squares solution of all the equations; the analytical route solves a square
// subsystem exactly, where no weight acts, so `auto` leaves it out when the weighting is asked for.
methods::AnalyticalOutcome analytical_solution(const TwoStepContext& ctx, const std::vector<int>& free,
                                               const Eigen::VectorXd& minimum) {
  const std::string& solver = ctx.two_step.solver;
  methods::AnalyticalOutcome analytical;
  if (ctx.whitened && solver == "analytical")
    throw FitError("two-step: the analytical route solves a square subsystem exactly, where the covariance weighting "
                   "has nothing to weight; use the minimisation route (or auto) with it");
  if (ctx.whitened && solver == "auto") {
    analytical.reason = "not tried: the covariance weighting asks for the weighted least-squares solution";
    analytical.details = {{"available", nullptr}, {"reason", analytical.reason}};
  } else if (solver == "auto" || solver == "analytical") {
    analytical = methods::analytical_route(ctx.model, ctx.one.tfs, free, ctx.setup.prior, minimum, ctx.two_step.analytical);
    if (!analytical.solved && solver == "analytical")
      throw FitError("two-step: the analytical route cannot be taken: " + analytical.reason);
  } else {
    analytical.reason = "not tried: route " + std::string(solver == "newton" ? "numerical" : solver) + " asked for";
    analytical.details = {{"available", nullptr}, {"reason", analytical.reason}};
  }
  return analytical;
}

// The estimate and the route that gave it.
struct StepTwoEstimate {
  Eigen::VectorXd values;
  std::string solver;  // "analytical", "newton" or "minimisation"
};

// The estimate (the thesis's Table 3.2): the analytical solution where there is an admissible one, else Newton's
// admissible root nearest the minimum where the system is square (the numerical solution before the minimisation),
// else the minimum.
StepTwoEstimate choose_estimate(const TwoStepContext& ctx, const StepTwoUnknowns& u, const Eigen::VectorXd& minimum,
                                const NewtonRoots& newton, const methods::AnalyticalOutcome& analytical) {
  StepTwoEstimate e{minimum, "minimisation"};
  if (analytical.solved) {
    e.values = analytical.values;
    e.solver = "analytical";
  } else if (u.square && ctx.two_step.solver != "minimisation") {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& r : newton.roots) {
      if (!r.admissible) continue;
      double d = 0;
      for (int i : u.free) d += std::pow(std::log(std::abs(r.values[i]) / std::max(std::abs(minimum[i]), 1e-300)), 2);
      if (d < nearest) {
        nearest = d;
        e.values = r.values;
        e.solver = "newton";
      }
    }
    if (ctx.two_step.solver == "newton" && e.solver != "newton")
      throw FitError("two-step: Newton's method found no admissible root of the coefficient equations from " +
                     std::to_string(std::max(1, ctx.options.starts) + 1) + " starts");
  }
  return e;
}

// The free parameters' covariance and how it was had, and step two's residual and model coefficients at the
// estimate.
struct StepTwoUncertainty {
  Eigen::MatrixXd covariance;  // of `free`; empty where step one gives none
  std::string note;
  Eigen::VectorXd residual, model_coefficients;
};

// Uncertainty: step one's coefficient covariance through step two's linearisation at the estimate (sandwich), or
// through the exact solution of the analytical route's square subsystem; none where step one has none (records).
StepTwoUncertainty propagate_uncertainty(const TwoStepContext& ctx, const std::vector<int>& free,
                                         const StepTwoEstimate& estimate, const methods::AnalyticalOutcome& analytical) {
  StepTwoUncertainty u;
  Eigen::MatrixXd J_est;
  ctx.problem.evaluate(estimate.values, free, u.residual, &J_est, &u.model_coefficients);
  const Eigen::MatrixXd sigma_hat = ctx.problem.identified_covariance();
  if (estimate.solver == "analytical" && analytical.covariance.size()) {
    u.covariance = analytical.covariance;
    u.note = "step one's coefficient covariance propagated through the exact solution of the chosen square "
             "subsystem S: J_S^-1 S_S J_S^-T";
  } else if (sigma_hat.size()) {
    const Eigen::MatrixXd W = ctx.problem.weight();
    Eigen::VectorXd sc(static_cast<Eigen::Index>(free.size()));
    for (std::size_t j = 0; j < free.size(); ++j)
      sc[static_cast<Eigen::Index>(j)] = std::max(std::abs(estimate.values[free[j]]), 1e-300);
    const Eigen::MatrixXd Js = J_est * sc.asDiagonal();
    const Eigen::MatrixXd Hi = pinv_spd(Js.transpose() * Js);
    const Eigen::MatrixXd Sw = W * sigma_hat * W.transpose();
    u.covariance = sc.asDiagonal() * (Hi * Js.transpose() * Sw * Js * Hi) * sc.asDiagonal();
    u.note = "step one's coefficient covariance propagated through step two's linearisation at the estimate: "
             "(J^T W J)^-1 J^T W S W J (J^T W J)^-1";
  } else {
    u.note = "std null: " + ctx.one.tfs.front().tf.covariance_note;
    for (const auto& s : ctx.one.tfs)
      if (s.tf.covariance.size() == 0) u.note = "std null: " + s.tf.covariance_note;
  }
  return u;
}

// Finish: parameters the estimate pressed against a bound held there; the interior ones estimated, with their part
// of the covariance (NaN-filled where there is none: the matrices keep the size of `estimated`, as fit.hpp has them);
// each candidate's verdicts, its std from the whole covariance of the free parameters (those held at a bound
// included); and step two's singular values, not the output-error Jacobian's.
FitResult finish(const TwoStepContext& ctx, const StepTwoUnknowns& u, Eigen::VectorXd values, const Eigen::MatrixXd& cov,
                 const Minimisation& minimisation) {
  const ModelInfo& info = ctx.info;
  const std::vector<int>& free = u.free;
  const std::vector<int>& candidates = ctx.setup.candidates;
  const std::vector<ParameterTransform>& transforms = ctx.setup.transforms;
  methods::MethodOutcome outcome;
  outcome.method = "two-step";
  outcome.prior = ctx.setup.prior;

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
  for (std::size_t j : interior) outcome.estimated.push_back(info.parameters[static_cast<std::size_t>(free[j])].name);
  if (cov.size() && !interior.empty()) {
    outcome.covariance.resize(static_cast<Eigen::Index>(interior.size()), static_cast<Eigen::Index>(interior.size()));
    for (std::size_t a = 0; a < interior.size(); ++a)
      for (std::size_t b = 0; b < interior.size(); ++b)
        outcome.covariance(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
            cov(static_cast<Eigen::Index>(interior[a]), static_cast<Eigen::Index>(interior[b]));
  } else if (!interior.empty()) {
    const Eigen::Index k = static_cast<Eigen::Index>(interior.size());
    outcome.covariance = Eigen::MatrixXd::Constant(k, k, std::numeric_limits<double>::quiet_NaN());
  }
  outcome.values = values;
  outcome.singular_values =
      analyse_identifiability(scaled_jacobian(ctx, candidates, values), identifiability_options(ctx.options))
          .singular_values;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const int i = candidates[c];
    methods::ReportedParameter p;
    p.index = i;
    ParameterEstimate& e = p.verdicts;
    e.estimated = u.identifiable[c];
    e.identifiable = u.identifiable[c] && !at_bound.count(i);
    if (at_bound.count(i)) e.at_bound = at_bound[i];
    e.std = std::numeric_limits<double>::quiet_NaN();
    const auto it = std::find(free.begin(), free.end(), i);
    if (it != free.end() && cov.size()) {
      const Eigen::Index j = it - free.begin();
      e.std = std::sqrt(std::max(cov(j, j), 0.0));
    }
    std::vector<int> conf = u.confounded[c];
    std::sort(conf.begin(), conf.end());
    conf.erase(std::unique(conf.begin(), conf.end()), conf.end());
    for (int o : conf) e.confounded_with.push_back(info.parameters[static_cast<std::size_t>(o)].name);
    outcome.parameters.push_back(p);
  }
  outcome.fitted = static_cast<int>(free.size());
  FitResult result;
  methods::finish_result(ctx.model, ctx.data, ctx.options, outcome, result);
  for (const auto& run : minimisation.runs) result.start_costs.push_back(run.cost);
  result.best_start = minimisation.best_start;
  const estimation::LmResult& best = minimisation.runs[static_cast<std::size_t>(minimisation.best_start)];
  result.iterations = best.iterations;
  result.converged = best.converged;
  result.stop_reason = best.stop_reason;
  result.cost_history = best.history;
  return result;
}

// method_details.step_two: the route and why, the coefficients compared, each route's own outcome and the
// uncertainty's source.
nlohmann::json step_two_details(const TwoStepContext& ctx, const StepTwoUnknowns& u, const Minimisation& minimisation,
                                const NewtonRoots& newton, const methods::AnalyticalOutcome& analytical,
                                const StepTwoEstimate& estimate, const StepTwoUncertainty& uncertainty,
                                std::string& route, std::string& route_reason) {
  const std::string& solver = estimate.solver;
  const Eigen::Index n_eq = ctx.n_eq;
  nlohmann::json start_costs = nlohmann::json::array();
  for (const auto& run : minimisation.runs) start_costs.push_back(number(run.cost));
  nlohmann::json coefficients = nlohmann::json::array();
  double q_tf = 0;  // the thesis's Eq. 3.99 whatever the weighting
  for (Eigen::Index i = 0; i < n_eq; ++i) {
    const double v = ctx.problem.targets()[static_cast<std::size_t>(i)].value;
    q_tf += std::pow((uncertainty.model_coefficients[i] - v) / v, 2);
  }
  for (Eigen::Index i = 0; i < n_eq; ++i) {
    const methods::CoefficientTarget& t = ctx.problem.targets()[static_cast<std::size_t>(i)];
    const methods::StepOneTf& s = ctx.one.tfs[t.tf];
    const double model = uncertainty.model_coefficients[i];
    coefficients.push_back({{"data", s.file},
                            {"polynomial", t.channel < 0 ? "denominator" : s.tf.outputs[static_cast<std::size_t>(t.channel)] + "/" + s.tf.input},
                            {"power", t.power},
                            {"identified", number(t.value)},
                            {"model", number(model)},
                            {"relative_mismatch", number((model - t.value) / std::abs(t.value))}});
  }
  route = solver == "newton" ? "numerical" : solver;
  if (solver == "analytical") {
    route_reason = "the exact solution of " + std::to_string(analytical.equations.size()) + " of the " +
                   std::to_string(n_eq) + " coefficient equations";
  } else {
    const std::string& asked = ctx.two_step.solver;
    route_reason = asked == "auto" ? "analytical route not taken: " + analytical.reason + "; " : "";
    route_reason += solver == "newton"       ? "Newton's admissible root of the square system"
                    : !u.square              ? "the minimisation (the least-squares solution of the overdetermined system)"
                    : asked == "minimisation" ? "the minimisation, as asked"
                                              : "the minimisation (Newton found no admissible root)";
  }
  const estimation::LmResult& best = minimisation.runs[static_cast<std::size_t>(minimisation.best_start)];
  return {{"route", route},
          {"route_reason", route_reason},
          {"solver", solver},
          {"equations", n_eq},
          {"unknowns", static_cast<int>(u.free.size())},
          {"weighting", ctx.whitened ? "covariance: the normalised mismatches whitened by step one's covariance"
                                     : "normalised by the identified coefficient (thesis Eq. 3.98)"},
          {"q_tf", number(q_tf)},
          {"cost", number(uncertainty.residual.squaredNorm())},
          {"coefficients", coefficients},
          {"minimisation", {{"starts", std::max(1, ctx.options.starts)}, {"best_start", minimisation.best_start},
                            {"starts_at_best", minimisation.at_best}, {"cost", number(best.cost)},
                            {"start_costs", start_costs}}},
          {"newton", newton.details},
          {"analytical", analytical.details},
          {"uncertainty", uncertainty.note}};
}

// method_details.two_step: a summary, step one's and step two's details, and the checks of the identified transfer
// functions against the model's at the estimate (zero-pole maps, suspect poles).
nlohmann::json two_step_details(const TwoStepContext& ctx, const Eigen::VectorXd& values, nlohmann::json step_two,
                                const std::string& route, const std::string& route_reason) {
  nlohmann::json zero_pole = nlohmann::json::array(), checks = nlohmann::json::array();
  int suspect = 0;
  for (const methods::StepOneTf& s : ctx.one.tfs) {
    Eigen::VectorXd v = values;
    for (const auto& [p, value] : s.overrides) v[p] = value;
    const methods::Validation val = methods::validate(
        s, s.truncated_to.empty() ? methods::model_tf(ctx.model, v, s.input, s.outputs, {})
                                  : methods::model_tf_truncated(ctx.model, v, s.input, s.outputs, s.truncated_to, {}));
    zero_pole.push_back(val.zero_pole);
    checks.push_back(val.checks);
    suspect += val.suspect_poles;
  }
  nlohmann::json details;
  details["summary"] = "step two by the " + route + " route: " + route_reason +
                       (ctx.whitened ? "; residuals whitened by step one's coefficient covariance" : "");
  details["step_one"] = ctx.one.details;
  details["step_two"] = std::move(step_two);
  details["zero_pole"] = zero_pole;
  details["checks"] = {{"transfer_functions", checks},
                       {"verdict", suspect ? "suspect: " + std::to_string(suspect) + " identified poles fail a check"
                                           : "valid: every identified pole passes the checks"}};
  return details;
}

}  // namespace

// check_options -> step one (TwoStepContext) -> unknowns_at_prior -> minimise_mismatch -> newton_roots
// -> analytical_solution -> choose_estimate -> propagate_uncertainty -> finish (+ the details)
FitResult fit_two_step(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                       const TwoStepOptions& two_step) {
  check_options(two_step);
  if (data.empty()) throw FitError("two-step: no data");
  const TwoStepContext ctx(model, data, options, two_step);
  if (two_step.weighting == "covariance" && !ctx.whitened)
    throw FitError("two-step: covariance weighting needs step one's coefficient covariance, which time records "
                   "(ARX, ARMAX) do not give");
  const StepTwoUnknowns unknowns = unknowns_at_prior(ctx);
  const std::vector<Eigen::VectorXd> start_points =
      estimation::start_points(ctx.search.internal(unknowns.free, ctx.setup.prior), unknowns.free,
                               ctx.setup.transforms, options);
  const Minimisation minimisation = minimise_mismatch(ctx, unknowns.free, start_points);
  const NewtonRoots newton = newton_roots(ctx, unknowns, minimisation.minimum, start_points);
  const methods::AnalyticalOutcome analytical = analytical_solution(ctx, unknowns.free, minimisation.minimum);
  const StepTwoEstimate estimate = choose_estimate(ctx, unknowns, minimisation.minimum, newton, analytical);
  const StepTwoUncertainty uncertainty = propagate_uncertainty(ctx, unknowns.free, estimate, analytical);

  FitResult result = finish(ctx, unknowns, estimate.values, uncertainty.covariance, minimisation);
  std::string route, route_reason;
  nlohmann::json step_two =
      step_two_details(ctx, unknowns, minimisation, newton, analytical, estimate, uncertainty, route, route_reason);
  result.method_details["two_step"] =
      two_step_details(ctx, result.values, std::move(step_two), route, route_reason).dump();
  return result;
}

}  // namespace mbgen
