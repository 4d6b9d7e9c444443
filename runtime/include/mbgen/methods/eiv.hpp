// Errors in variables (docs/methods.md#eiv): the physical parameters from time records whose measured force is
// noisy too, by the frequency-domain maximum-likelihood (Schoukens-Pintelon) cost with input and output noise.
//
//   FitResult r = mbgen::fit_eiv(model, records, options);   // r.method == "eiv"
//
// Starts from the output-error fit (mbgen::fit with `options`: its global search, identifiability and bounds), then
// minimises the errors-in-variables cost over the parameters that fit left interior and identifiable, with the
// white noise levels of the force and of each output estimated from the data alongside; the covariance is the
// Gauss-Newton one of that cost. Time records only (FitError otherwise); each must hold every model input (the
// measured force: DataError otherwise). method_details["eiv"] holds the noise levels found, the output-error
// estimate it started from, and the cost.
#pragma once

#include "mbgen/estimation/fit.hpp"

namespace mbgen {

FitResult fit_eiv(const Model& model, const std::vector<DataSet>& data, const FitOptions& options = {});

}  // namespace mbgen
