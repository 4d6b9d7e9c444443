// judging -- the rules that decide, from fitted models alone, whether a round's best candidate is taken and whether
// the extensions taken are kept (docs/diagnosis.md, steps 7 and 8). Pure functions of fitted states: the loop
// (diagnose.cpp) fits, calls them and reports their reasons; judging_test.cpp checks them on hand-made states.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "diagnosis/engine/diagnose.hpp"

namespace mbgen::diagnosis {

// A rule's decision and the reason to report. `why` may be set when the rule holds (a partial explanation taken
// for a further round); `still` lists the nominal findings the rule found still showing, for the report.
struct Judgement {
  bool holds = true;
  std::string why;
  std::vector<const Discrepancy*> still;
};

// The mean normalized residual over finding d's band, on its channel and data set; minus one when the channels
// have no such lines.
double band_mean_z(const std::vector<ChannelResidual>& channels, const Discrepancy& d);

// Whether `extended` still shows the finding d of the model whose channels are `nominal` (`threshold`: the one that
// made d a finding): the residual over d's band stays above the threshold or its excess over the noise does not
// halve. A parameter_at_bound finding shows while the extended fit presses the same parameter against a bound.
bool still_shows(const std::vector<ChannelResidual>& nominal, const ModelState& extended, const Discrepancy& d,
                 double threshold);

// The nominal model's findings that `before` still shows and `after` no longer does: what the extension taking
// `before` to `after` explains, by index into result.nominal.residual.discrepancies.
std::vector<std::size_t> findings_cleared(const DiagnosisResult& result, const ModelState& before,
                                          const ModelState& after);

// The nominal model's findings that `current` still shows, by index into result.nominal.residual.discrepancies:
// what a further round may still explain. Where none is left and the extended model would be kept, findings only
// it shows are the form of the extensions taken (an approximate base's own misfit), not a further effect.
std::vector<std::size_t> pending_findings(const DiagnosisResult& result, const ModelState& current);

// The qualifying candidate with the lowest BIC (ties within thresholds::kBicTie to the first), or -1.
int best_qualifying(const std::vector<CandidateOutcome>& outcomes);

// The BIC winner `best` must also predict the held-back data about as well as any other qualifying candidate.
Judgement predicts_as_well(const std::vector<CandidateOutcome>& outcomes, int best);

// Whether `chosen` explains what `current` gets wrong: the residual's excess over the noise at least halves; or,
// while `rounds_left` further rounds may follow, it lowers the excess and clears one of current's findings, at a
// pace (thresholds::kPartialPaceMargin) at which those rounds could bring the mean normalized residual down to
// `final_residual`, what the extended model must reach in the end. `own_output`, when given (a sensor's dynamics):
// only a finding on that output counts as cleared by a partial explanation.
Judgement explains(const ModelState& current, const ModelState& chosen, int rounds_left, double final_residual,
                   const std::string& own_output = "");

// Whether the extensions that took the nominal model to `current` together explain enough to be kept: the residual
// near the noise (options.max_final_residual), the nominal model's strongest finding cleared, no mode moved that the
// nominal model had right, and at most options.max_remaining_findings of its findings left.
Judgement full_explanation(const DiagnosisResult& result, const ModelState& current, const DiagnoseOptions& options);

// "extended", "unexplained" (findings and nothing selected) or "no_extension_justified".
std::string verdict_of(const DiagnosisResult& result);

}  // namespace mbgen::diagnosis
