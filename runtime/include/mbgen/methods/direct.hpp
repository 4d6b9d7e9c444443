// The "direct" method (Nickel 1999, Sec. 3.6.1; docs/methods.md#direct): the equations of motion
// M q'' + C q' + K q = B u as algebraic equations in the physical parameters, given the measured forces and the
// motion of every coordinate the forces move, solved in the frequency domain by instrumental variables.
//
//   FitResult r = mbgen::fit_direct(model, data, options);   // r.method == "direct"
//
// Data: FRFs (per input, outputs that give every excited coordinate: as many independent ones as coordinates) or
// time records (the same, all outputs of one kind). Parameters of role Estimate (or FitOptions::estimate) are solved
// for; the others are known at their values (FitOptions::values). Throws FitError (exit status 1), naming the
// coordinates the outputs cannot give, when the data do not allow it. The result's nrmse, bic and cost are those of
// the output-error residual at the estimate (comparable with mbgen::fit); method_details["direct"] holds the
// equation-error numbers, the ordinary least-squares estimate, the coordinates used and the conditioning.
#pragma once

#include "mbgen/estimation/fit.hpp"

namespace mbgen {

FitResult fit_direct(const Model& model, const std::vector<DataSet>& data, const FitOptions& options = {});

}  // namespace mbgen
