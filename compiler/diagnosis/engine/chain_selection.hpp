// chain_selection -- which of the measurement chain's candidates a round fits (docs/diagnosis.md, "The measurement
// chain"): those whose statistic at the current fit, or against the priors, says the data would support them.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "diagnosis/engine/diagnose.hpp"
#include "diagnosis/engine/driving_points.hpp"

namespace mbgen::diagnosis {

// The chain candidates among `extensions` whose statistic says the data would support them (chain_scores.hpp): a
// factor on an output's (or an input's) channels whose score statistic exceeds ln(n), the BIC price of the factor
// with n residuals, in the variants of the factor's sign only (calibration g > 0; polarity g < 0 and reversed
// g = -1); two outputs whose exchanged data lower chi-square by more than ln(n); an output whose data fit better as
// another form of its quantity (form_gain) by more than ln(n). The three best by statistic are fitted; a driving
// point that gives out power (`reversed_points`, driving_points.hpp) puts its force's and its sensor's negative
// variants first. The statistics take milliseconds: where the data's chain is right, no chain candidate is fitted.
// `current`: the current model's fit and channels; `prior_channels`: the data against the current model at its
// priors; `say`: a progress line per candidate kept, with its evidence.
std::vector<Extension> chain_candidates_worth_fitting(std::vector<Extension> extensions, const ModelState& current,
                                                      const std::vector<ChannelResidual>& prior_channels,
                                                      const std::vector<ReversedDrivingPoint>& reversed_points,
                                                      const std::function<void(const std::string&)>& say);

}  // namespace mbgen::diagnosis
