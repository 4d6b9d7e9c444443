// The one finisher of every estimation method beside output error (docs/methods.md): whatever a method minimised,
// its result reports the parameters it estimates with their prior values and its verdicts on them, and the
// output-error numbers of its estimate, so that methods compare on one scale. What differs between methods (which
// parameters it reports and its verdicts on each, its covariance, which parameters score the identifiability) is
// given as data in a MethodOutcome. Internal header.
#pragma once

#include "estimation/fit_inputs.hpp"
#include "mbgen/estimation/fit.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mbgen::methods {

// The prior values, checked, and the parameters to estimate: as mbgen::fit takes them (fit_inputs.hpp).
using estimation::candidate_parameters;
using estimation::checked_prior;

// One parameter the result reports, with the method's verdicts on it.
struct ReportedParameter {
  int index = 0;  // the model parameter
  // estimated, identifiable, at_bound, confounded_with, std, pull_chi2, toward as the method judged them; its name,
  // unit, prior and value are the finisher's (from the model, MethodOutcome::prior and ::values).
  ParameterEstimate verdicts;
};

// What a method found, as the finisher takes it.
struct MethodOutcome {
  std::string method;      // FitResult::method, as --method names it
  Eigen::VectorXd prior;   // all model parameters: the values the method started from (the model's, --set, --fix)
  Eigen::VectorXd values;  // all model parameters at the estimate
  std::vector<ReportedParameter> parameters;  // FitResult::parameters, in this order (the candidates)
  std::vector<std::string> estimated;         // the parameters of the covariance, in its order
  Eigen::MatrixXd covariance;  // of `estimated`, physical units; empty: none; NaN: not known (sized as `estimated`)
  // Each of `estimated` takes its std from the covariance's diagonal; false: the verdicts' std stands (a method whose
  // covariance covers parameters it then held at a bound).
  bool std_from_covariance = false;
  // The output-error scoring: the parameters whose Jacobian gives FitResult::singular_values (empty: the method's
  // own `singular_values` stand) and how many were fitted (the BIC's k).
  std::vector<int> scored;
  Eigen::VectorXd singular_values;
  int fitted = 0;
};

// The verdicts of a parameter the method estimated, with no more to say of it than that.
ReportedParameter estimated_parameter(int index);

// Fills the members of `result` every method shares from `outcome`: model (the model's name), data (the files),
// method, prior_values, values, parameters, estimated, covariance, correlation; and, from the output-error residual
// (the statistically weighted residual mbgen::fit minimises, `options.frf_weighting`) at the estimate,
// residual_count, cost, initial_cost (at the prior), residual_variance, nrmse, bic, singular_values (of the
// column-scaled output-error Jacobian of `outcome.scored`) and the modes. Its convergence members (iterations,
// converged, stop_reason, cost_history) and method_details are the method's; other members of `result` are kept.
void finish_result(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                   const MethodOutcome& outcome, FitResult& result);

// The output-error cost (weighted residual sum of squares, as mbgen::fit's) at `values`.
double output_error_cost(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                         const Eigen::VectorXd& values);

}  // namespace mbgen::methods
