// Step one of the two-step method over all data sets: per data set and driven input, a black-box transfer function
// of the model's order (rational_fit.hpp for FRFs, arx.hpp for time records) and its details for method_details.
// Internal header.
#pragma once

#include "coefficient_problem.hpp"
#include "mbgen/estimation/fit.hpp"
#include "mbgen/methods/two_step.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace mbgen::methods {

struct StepOne {
  std::vector<StepOneTf> tfs;
  nlohmann::json details;  // array, one entry per transfer function
};

// `prior`: all parameter values; `candidates`: the parameters step two may move (for the structural pattern).
// Throws FitError naming the file for data the method cannot use.
// `threads`: for the ARMAX searches' starts.
StepOne run_step_one(const Model& model, const std::vector<DataSet>& data, const Eigen::VectorXd& prior,
                     const std::vector<int>& candidates, const TwoStepOptions& options, int threads = 1);

}  // namespace mbgen::methods
