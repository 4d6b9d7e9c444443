// What every estimation method beside output error shares (docs/methods.md): the parameters it estimates, their
// prior values, and the output-error numbers of its estimate, so that methods compare on one scale. Internal header.
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

// The members of a result that say what was run: model (the model's name), data (the files), method, prior_values.
void describe_run(const ModelInfo& info, const std::vector<DataSet>& data, const std::string& method,
                  const Eigen::VectorXd& prior, FitResult& r);

// Model parameter i's estimate before the method's verdicts on it: its name, unit, prior and value.
ParameterEstimate parameter_estimate(const ModelInfo& info, int i, const Eigen::VectorXd& prior,
                                     const Eigen::VectorXd& values);

// The output-error cost (weighted residual sum of squares, as mbgen::fit's) at `values`.
double output_error_cost(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                         const Eigen::VectorXd& values);

// Fills, from the output-error residual (the statistically weighted residual mbgen::fit minimises) at
// result.values: residual_count, cost, initial_cost (at result.prior_values), residual_variance, nrmse, bic with
// `fitted` parameters, singular_values (of the column-scaled output-error Jacobian of `candidates`), and the modes.
void score_by_output_error(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                           const std::vector<int>& candidates, int fitted, FitResult& result);

}  // namespace mbgen::methods
