// What the estimation methods beside output error share (ekf, arx-two-stage): the parameters to estimate and their
// priors, bounds transforms and checks, as mbgen::fit takes them from FitOptions; and the method-independent part
// of a FitResult (output-error cost and NRMSE of a simulation at the estimate, BIC, modes), so that every method's
// result can be compared with the output-error fit on the same terms. Internal header.
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

// Fills the method-independent members of `r` at the full parameter vector `values`: model, data, method,
// prior_values, values, residual_count, cost, initial_cost, residual_variance, nrmse and bic of the time-domain
// output error (each output divided by its measured RMS, a simulation from rest, as the output-error fit weighs
// it), and the modes. Parameters, covariance and the method's own members are the caller's.
void fill_common(const Model& model, const std::vector<DataSet>& data, const MethodSetup& setup,
                 const Eigen::VectorXd& values, const std::string& method, FitResult& r);

// r.covariance (physical units, of r.estimated, in that order) given; sets r.correlation and each estimated
// parameter's std in r.parameters.
void set_covariance(const Eigen::MatrixXd& covariance, FitResult& r);

}  // namespace mbgen::methods
