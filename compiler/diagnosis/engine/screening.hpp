// screening -- the cheap fits that decide which of a round's candidates are fitted fully (docs/diagnosis.md,
// "Screening").
#pragma once

#include <memory>
#include <vector>

#include "diagnosis/engine/model_fits.hpp"

namespace mbgen::diagnosis {

// Screening (DiagnoseOptions::full_fits): cheaper fits of every candidate, ranked by BIC against the current
// model fitted the same way; candidates outside the `full_fits` best are screened out: their outcome is the
// screening fit, and they cannot qualify. Fills `screen_delta_bic` of every candidate in `fitted`.
//  - On FRFs (the measured ones, or the records' H1 estimates: no simulation): a candidate that contains the
//    current model (Extension::nesting) descends from the point where it is the current model, once, to
//    convergence (the score test carried through); any other, two local fits to convergence, from the current
//    estimate and from the priors (the centres of the full fit's two searches, without its random starts,
//    validation or residual analysis), and one from each of the candidate's alternative starts.
//  - With time records also a few Gauss-Newton steps on the records from the current estimate: an effect the
//    records show but their H1 estimates' coarse lines blur (the gyroscopic split of the spindle's modes at
//    300 rev/s, a few Hz under 8 Hz lines: screening delta BIC +17.9 on the H1 estimates, -20681 fitted on the
//    records) shows in the time-domain cost at once. The kept candidates alternate between the two rankings.
// `evaluators`, `memos`: the candidates' derived models and local-fit memos; `fitted`: the candidates fitted in
// their own right (no twin); `states[k]` gets the screening fit of each; `screened_out[k]` is set for those left out.
void screen(const FitContext& fits, const std::vector<Extension>& extensions,
            const std::vector<std::unique_ptr<Model>>& evaluators,
            const std::vector<std::shared_ptr<estimation::LocalFitMemo>>& memos, const ModelState& base, int round,
            const std::vector<std::size_t>& fitted, std::vector<CandidateOutcome>& outcomes,
            std::vector<ModelState>& states, std::vector<char>& screened_out);

}  // namespace mbgen::diagnosis
