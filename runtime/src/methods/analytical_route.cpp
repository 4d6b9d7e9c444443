#include "analytical_route.hpp"

#include "estimation/value_checks.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mbgen::methods {

namespace {

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

// Sum of squared log ratios over `free`: the distance the Newton route also measures roots by.
double log_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const std::vector<int>& free) {
  double d = 0;
  for (int i : free) d += std::pow(std::log(std::abs(a[i]) / std::max(std::abs(b[i]), 1e-300)), 2);
  return d;
}

}  // namespace

bool admissible(const Model& model, const Eigen::VectorXd& v, const std::vector<int>& free) {
  const ModelInfo& info = model.info();
  for (int i : free) {
    const ParameterInfo& p = info.parameters[static_cast<std::size_t>(i)];
    if (!(v[i] >= p.lower && v[i] <= p.upper)) return false;
  }
  try {
    estimation::check_parameter_values(model, v, "two-step");
  } catch (const std::runtime_error&) {  // FitError, DynamicsError; a logic_error is a bug and goes on
    return false;
  }
  return true;
}

AnalyticalOutcome analytical_route(const Model& model, const std::vector<StepOneTf>& tfs, const std::vector<int>& free,
                                   const Eigen::VectorXd& prior, const Eigen::VectorXd& minimum,
                                   const AnalyticalSolver& solver) {
  const ModelInfo& info = model.info();
  AnalyticalOutcome out;
  auto unavailable = [&](const std::string& why) {
    out.reason = why;
    out.details = {{"available", false}, {"reason", why}};
    return out;
  };
  if (!solver) return unavailable("no exact solver in this program (the runtime library has no computer algebra)");
  for (const StepOneTf& s : tfs)
    if (!s.truncated_to.empty())
      return unavailable(s.file + " shows fewer modes than the model: the truncated model's coefficients (from its "
                         "eigenvalues) have no closed form");

  // The unwhitened normalised problem: the equations in the targets' order.
  const CoefficientProblem problem(model, tfs);
  const std::vector<CoefficientTarget>& targets = problem.targets();
  const auto n_eq = static_cast<Eigen::Index>(targets.size());
  const auto n = static_cast<Eigen::Index>(free.size());
  CoefficientSystem system;
  for (const StepOneTf& s : tfs) system.tfs.push_back({s.file, s.input, s.outputs, s.overrides, s.tf.order()});
  {
    Eigen::VectorXd r, at_prior;
    problem.evaluate(prior, {}, r, nullptr, &at_prior);
    for (Eigen::Index i = 0; i < n_eq; ++i) {
      const CoefficientTarget& t = targets[static_cast<std::size_t>(i)];
      system.equations.push_back({t.tf, t.channel, t.power, t.value, at_prior[i]});
    }
  }
  system.unknowns = free;
  system.values = prior;
  AnalyticalSolution solution;
  try {
    solution = solver(system);
  } catch (const std::exception& e) {
    return unavailable(std::string("the exact solver failed: ") + e.what());
  }
  if (!solution.unavailable.empty()) return unavailable(solution.unavailable);

  // The normalised covariance of the identified coefficients (empty: none).
  Eigen::MatrixXd Sn = problem.identified_covariance();
  if (Sn.size()) Sn = problem.weight() * Sn * problem.weight().transpose();
  auto name_of = [&](int eq) { return solution.coefficient_names.at(static_cast<std::size_t>(eq)); };

  nlohmann::json subsystems = nlohmann::json::array();
  double best_score = std::numeric_limits<double>::infinity();
  int best_sub = -1, best_sol = -1;
  int with_solutions = 0;
  for (std::size_t k = 0; k < solution.subsystems.size(); ++k) {
    const AnalyticalSubsystem& sub = solution.subsystems[k];
    nlohmann::json js;
    js["equations"] = nlohmann::json::array();
    for (int e : sub.equations) js["equations"].push_back(name_of(e));
    js["closed_form"] = sub.closed_form;
    if (!sub.failure.empty()) js["failure"] = sub.failure;
    nlohmann::json sols = nlohmann::json::array();
    int candidate = -1;
    double candidate_distance = std::numeric_limits<double>::infinity(), candidate_score = 0;
    if (!sub.solutions.empty()) ++with_solutions;
    for (std::size_t j = 0; j < sub.solutions.size(); ++j) {
      const Eigen::VectorXd& v = sub.solutions[j];
      nlohmann::json s;
      nlohmann::json vals, exact;
      for (std::size_t u = 0; u < free.size(); ++u) {
        const std::string& name = info.parameters[static_cast<std::size_t>(free[u])].name;
        vals[name] = number(v[free[u]]);
        if (j < sub.exact.size() && u < sub.exact[j].size()) exact[name] = sub.exact[j][u];
      }
      s["values"] = vals;
      if (!exact.is_null()) s["exact"] = exact;
      std::string why;
      Eigen::VectorXd r;
      Eigen::MatrixXd J;
      bool evaluated = v.allFinite();
      if (evaluated) {
        try {
          problem.evaluate(v, free, r, &J);
        } catch (const std::runtime_error&) {  // DynamicsError there; a logic_error is a bug and goes on
          evaluated = false;
        }
      }
      if (!evaluated || !r.allFinite() || !J.allFinite()) {
        why = "the model cannot be evaluated there";
      } else {
        double own = 0;
        for (int e : sub.equations) own = std::max(own, std::abs(r[e]));
        s["max_mismatch_of_its_equations"] = number(own);
        nlohmann::json checks = nlohmann::json::array();
        double check_ss = 0;
        int check_count = 0;
        for (Eigen::Index e = 0; e < n_eq; ++e)
          if (std::find(sub.equations.begin(), sub.equations.end(), static_cast<int>(e)) == sub.equations.end()) {
            checks.push_back({{"coefficient", name_of(static_cast<int>(e))}, {"relative_mismatch", number(r[e])}});
            check_ss += r[e] * r[e];
            ++check_count;
          }
        s["checks"] = checks;
        const double check_rms = check_count ? std::sqrt(check_ss / check_count) : 0.0;
        s["checks_rms"] = number(check_rms);
        if (own > 1e-6) why = "does not satisfy its own equations numerically: the exact solver's coefficients are not the runtime's";
        else if (!admissible(model, v, free)) why = "inadmissible: outside the bounds or a mass matrix not positive definite";
        if (why.empty()) {
          // Sensitivity of the relative parameters to the subsystem's normalised coefficients.
          Eigen::MatrixXd Js(n, n);
          for (Eigen::Index a = 0; a < n; ++a)
            for (Eigen::Index b = 0; b < n; ++b) Js(a, b) = J(sub.equations[static_cast<std::size_t>(a)], b) * v[free[static_cast<std::size_t>(b)]];
          const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js);
          const Eigen::VectorXd sv = svd.singularValues();
          if (!(sv[n - 1] > sv[0] * 1e-13)) {
            why = "singular there: the subsystem does not determine the parameters locally";
          } else {
            double score = check_rms;
            if (Sn.size()) {
              const Eigen::MatrixXd G = Js.inverse();
              Eigen::MatrixXd S(n, n);
              for (Eigen::Index a = 0; a < n; ++a)
                for (Eigen::Index b = 0; b < n; ++b) S(a, b) = Sn(sub.equations[static_cast<std::size_t>(a)], sub.equations[static_cast<std::size_t>(b)]);
              score = std::sqrt((G * S * G.transpose()).trace() / double(n));
              s["predicted_rms_relative_error"] = number(score);
            }
            const double d = log_distance(v, minimum, free);
            if (d < candidate_distance) {
              candidate_distance = d;
              candidate = static_cast<int>(j);
              candidate_score = score;
            }
          }
        }
      }
      s["admissible"] = why.empty();
      if (!why.empty()) s["why_not"] = why;
      sols.push_back(s);
    }
    js["solutions"] = sols;
    subsystems.push_back(js);
    if (candidate >= 0 && candidate_score < best_score) {
      best_score = candidate_score;
      best_sub = static_cast<int>(k);
      best_sol = candidate;
    }
  }
  out.details = {{"available", true},
                 {"subsystem_choice", solution.subsystem_choice},
                 {"coefficients", solution.coefficient_names},
                 {"selection", Sn.size() ? "the smallest predicted error from step one's coefficient covariance"
                                         : "the smallest RMS normalised mismatch of the equations left out (no "
                                           "covariance from step one to predict errors by)"},
                 {"subsystems", subsystems}};
  if (best_sub < 0) {
    out.reason = solution.subsystems.empty() ? "no square subsystem to solve"
                 : with_solutions == 0       ? "no square subsystem has a closed-form real solution (" +
                                                   solution.subsystems.front().failure + ")"
                                             : "no real solution is admissible (within the bounds, a positive definite "
                                               "mass matrix) and regular";
    out.details["reason"] = out.reason;
    return out;
  }
  const AnalyticalSubsystem& chosen = solution.subsystems[static_cast<std::size_t>(best_sub)];
  out.solved = true;
  out.values = chosen.solutions[static_cast<std::size_t>(best_sol)];
  out.equations = chosen.equations;
  out.details["chosen"] = {{"subsystem", best_sub}, {"solution", best_sol}, {"score", number(best_score)}};
  // The uncertainty of an exact solution of S: dp = J_S^-1 D_S dL^_S.
  if (Sn.size()) {
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    problem.evaluate(out.values, free, r, &J);
    Eigen::MatrixXd JS(n, n), S(n, n);
    for (Eigen::Index a = 0; a < n; ++a) {
      JS.row(a) = J.row(out.equations[static_cast<std::size_t>(a)]);
      for (Eigen::Index b = 0; b < n; ++b) S(a, b) = Sn(out.equations[static_cast<std::size_t>(a)], out.equations[static_cast<std::size_t>(b)]);
    }
    const Eigen::MatrixXd Ji = JS.inverse();
    out.covariance = Ji * S * Ji.transpose();
  }
  return out;
}

}  // namespace mbgen::methods
