// What every estimator does before it fits (fit.cpp, the methods of runtime/src/methods). Internal header.
//
// prepare_fit: the prior (the model's values with FitOptions::values over them), the checks of those values and of
// the data (value_checks.hpp), the candidate parameters (FitOptions::estimate, else those of role Estimate) and
// their bounded transforms (parameterization.hpp). Throws FitError.
//
// start_points: the multi-start's starting points in internal coordinates: theta0 first, then `chosen` (starts of
// the caller's choosing), then points drawn from StartSampler(options.seed) uniformly within +-log(spread) of theta0 (multiplicatively
// for an unbounded parameter), so that a seed gives the same starts in every estimator.
#pragma once

#include "mbgen/estimation/fit.hpp"
#include "mbgen/estimation/parameterization.hpp"

#include <Eigen/Core>

#include <vector>

namespace mbgen::estimation {

struct FitSetup {
  Eigen::VectorXd prior;                       // all model parameters
  std::vector<int> candidates;                 // model indices, increasing
  std::vector<ParameterTransform> transforms;  // per model parameter; set for the candidates
};

FitSetup prepare_fit(const Model& model, const std::vector<DataSet>& data, const FitOptions& options);

// The full parameter vector with the `free` ones at internal coordinates theta (the others as in `base`), and back.
Eigen::VectorXd physical_values(const Eigen::VectorXd& base, const std::vector<int>& free,
                                const std::vector<ParameterTransform>& transforms, const Eigen::VectorXd& theta);
Eigen::VectorXd internal_values(const std::vector<int>& free, const std::vector<ParameterTransform>& transforms,
                                const Eigen::VectorXd& values);

std::vector<Eigen::VectorXd> start_points(const Eigen::VectorXd& theta0, const std::vector<int>& free,
                                          const std::vector<ParameterTransform>& transforms, const FitOptions& options,
                                          const std::vector<Eigen::VectorXd>& chosen = {});

}  // namespace mbgen::estimation
