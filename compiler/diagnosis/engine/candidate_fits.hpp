// candidate_fits -- a round's candidates fitted on the current model: derived, screened (screening.hpp), the kept
// ones fitted fully side by side on the cores, and judged (candidate_judging.hpp).
#pragma once

#include <vector>

#include "diagnosis/engine/model_fits.hpp"

namespace mbgen::diagnosis {

// Derives every candidate, fits those that are not the same model as an earlier one (same_response.hpp) on
// worker threads, and gives each of the others the fit of its twin. Outcomes and states are in the order of
// `extensions`, and so are the progress lines. `base`: the current model, which the candidates extend.
void score_all(const FitContext& fits, const std::vector<Extension>& extensions, const ModelState& base, int round,
               std::vector<CandidateOutcome>& outcomes, std::vector<ModelState>& states);

}  // namespace mbgen::diagnosis
