// What every estimation method beside output error shares (docs/methods.md): the parameters it estimates, their
// prior values, and the output-error numbers of its estimate, so that methods compare on one scale. Internal header.
#pragma once

#include "mbgen/fit.hpp"

#include <Eigen/Core>

#include <vector>

namespace mbgen::methods {

// The model's values with FitOptions::values over them, checked as mbgen::fit checks them (bounds, a positive
// definite mass matrix, the data sets' `# set` values, signals that are not zero throughout). Throws FitError.
Eigen::VectorXd checked_prior(const Model& model, const std::vector<DataSet>& data, const FitOptions& options);

// The candidates for estimation, in model order: FitOptions::estimate, or else the parameters of role Estimate.
std::vector<int> candidate_parameters(const ModelInfo& info, const FitOptions& options);

// The output-error cost (weighted residual sum of squares, as mbgen::fit's) at `values`.
double output_error_cost(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                         const Eigen::VectorXd& values);

// Fills, from the output-error residual (the statistically weighted residual mbgen::fit minimises) at
// result.values: residual_count, cost, initial_cost (at result.prior_values), residual_variance, nrmse, bic with
// `fitted` parameters, singular_values (of the column-scaled output-error Jacobian of `candidates`), and the modes.
void score_by_output_error(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                           const std::vector<int>& candidates, int fitted, FitResult& result);

}  // namespace mbgen::methods
