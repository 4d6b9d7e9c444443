// The "hybrid" method (Nickel 1999, Sec. 3.6.6; docs/methods.md#hybrid): a cheap closed-form estimate, the direct
// method's, refined by output error (mbgen::fit) started from it.
//
//   FitResult r = mbgen::fit_hybrid(model, data, options);   // r.method == "hybrid"
//
// The output-error fit takes the direct estimate as its prior (start 0, and the centre of its random starts) and
// the model's own values as start 1, so it never does worse than the output-error fit from the model's values
// alone. Needs what the direct method needs (throws its FitError otherwise). method_details["hybrid"] says what
// was combined and holds both estimates; method_details["direct"] is the direct method's own.
#pragma once

#include "mbgen/estimation/fit.hpp"

namespace mbgen {

FitResult fit_hybrid(const Model& model, const std::vector<DataSet>& data, const FitOptions& options = {});

// Where an output-error fit started from another method's estimate starts parameter `p`: at the estimate, or, for a
// parameter the method left at a bound, just inside it (a bound is the edge of the output-error fit's
// reparameterisation).
double start_inside_bounds(const ParameterEstimate& estimate, const ParameterInfo& p);

}  // namespace mbgen
