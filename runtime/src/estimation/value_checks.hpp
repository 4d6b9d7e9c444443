// Checks of what a fit is given, made before fitting so that a bad value or an empty signal is reported as bad input
// instead of giving NaN or meaningless results: parameter values within their declared bounds and with a positive
// definite mass matrix (a zero or negative mass gives modes with damping ratios of +-1), and measured signals that
// are not zero (or too small to square) throughout.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "mbgen/estimation/fit.hpp"

namespace mbgen::estimation {

// Throws FitError, naming `where` (e.g. "--set values") and the parameter.
void check_parameter_values(const Model& model, const Eigen::VectorXd& values, const std::string& where);

// Each data set's `# set` values, applied over `prior`: DataError at the `# set` line.
void check_data_set_values(const Model& model, const Eigen::VectorXd& prior, const std::vector<DataSet>& data);

// Throws DataError for a measured FRF channel or a time record's output zero throughout or below
// kMinSignalMagnitude (mbgen/data/data_set.hpp) throughout, or a record whose inputs all are.
void check_measured_signals(const Model& model, const std::vector<DataSet>& data);

}  // namespace mbgen::estimation
