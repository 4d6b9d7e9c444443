// The setup of the estimation methods on time records beside output error (ekf, arx-two-stage): the parameters to
// estimate and their priors, bounds transforms and checks, as mbgen::fit takes them from FitOptions. Their results
// are finished as every method's are (method_result.hpp). Internal header.
#pragma once

#include "estimation/fit_setup.hpp"
#include "mbgen/estimation/fit.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mbgen::methods {

// The setup is output error's own (estimation/fit_setup.hpp): the prior of all model parameters (defaults with
// FitOptions::values over them), the parameters to estimate (`candidates`: FitOptions::estimate, or the role
// Estimate) and their bounds transforms.
using MethodSetup = estimation::FitSetup;

// Checks the values and the data as fit() does (FitError / DataError) and that every data set is a time record
// (`method` names the method in the message: "--method ekf needs time records ...").
MethodSetup method_setup(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                         const std::string& method);

// The parameter vector for data set `d`: `values` with its `# set` lines over them.
Eigen::VectorXd values_for(const Model& model, const DataSet& d, const Eigen::VectorXd& values);

}  // namespace mbgen::methods
