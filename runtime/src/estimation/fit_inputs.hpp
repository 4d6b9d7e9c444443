// What every estimator takes from FitOptions before it starts (mbgen::fit and the methods of docs/methods.md): the
// prior values, checked, and the parameters to estimate. Internal header.
#pragma once

#include "mbgen/estimation/fit.hpp"
#include "mbgen/estimation/identifiability.hpp"

#include <Eigen/Core>

#include <vector>

namespace mbgen::estimation {

// The model's values with FitOptions::values over them, checked: names, bounds, a positive definite mass matrix,
// the data sets' `# set` values, measured signals that are not zero throughout. Throws FitError (DataError).
Eigen::VectorXd checked_prior(const Model& model, const std::vector<DataSet>& data, const FitOptions& options);

// The candidates for estimation, in model order: FitOptions::estimate, or else the parameters of role Estimate.
std::vector<int> candidate_parameters(const ModelInfo& info, const FitOptions& options);

// The identifiability analysis's tolerances, as FitOptions gives them.
IdentifiabilityOptions identifiability_options(const FitOptions& options);

}  // namespace mbgen::estimation
