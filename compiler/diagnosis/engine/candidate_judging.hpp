// candidate_judging -- the judgement of one fitted candidate, and of a fit's parameters against their bounds: pure
// functions of fitted states (no fitting), used by the loop (diagnose.cpp) and the candidate fits
// (candidate_fits.cpp) and checked on hand-made fits in candidate_judging_test.cpp. The rules that compare
// candidates and models (take, keep, verdict) are judging.hpp's.
#pragma once

#include <string>
#include <vector>

#include <mbgen/model.hpp>

#include "diagnosis/engine/diagnose.hpp"

namespace mbgen::diagnosis {

// The measurement chain's operator (docs/diagnosis.md, "The measurement chain"): its candidates are fitted only where
// a statistic at the current fit or against the priors supports them (chain_selection.hpp), and their description
// names the channel and the factor.
inline constexpr const char* kChainOperator = "measurement_chain";

// Whether the fit pressed an estimate against one of its bounds: it stands at the bound (within a thousandth of
// it, or, for a bound at zero, below a thousandth of its prior: the bounded fit approaches zero by factors, never
// reaching it) and the data pull it further out (more than 10 in chi-square: ParameterEstimate::pull_chi2). A
// parameter the data barely see may drift to a bound with nothing pulling it: that is no misfit. "upper" or
// "lower", or empty.
std::string pressed_bound(const ParameterEstimate& p, const ParameterInfo& info);

// Findings of a fit that needs values its model does not allow: each estimate pressed against a bound.
std::vector<Discrepancy> bound_findings(const FitResult& fit, const ModelInfo& info);

// A candidate's name on progress lines: its id, and its variant in parentheses.
std::string label(const Extension& ext);

// The outcome of candidate `ext` in `round` before any fit: its id, description and parameters.
CandidateOutcome outline(const Extension& ext, int round);

// The outcome of a candidate that could not be derived or fitted.
CandidateOutcome failed(const Extension& ext, int round, const std::string& error);

// A fully fitted candidate's result on its progress line: delta BIC, validation, and why it is implausible.
std::string fitted_text(const CandidateOutcome& o);

// The candidate's new parameters that its fit could not determine: not identifiable or known to no better than
// 50 % (the plausibility rule's measures), and not held against a bound by the data (a parameter pressed against a
// bound is a doubt of its own).
std::vector<std::string> undetermined_new_parameters(const Extension& ext, const FitResult& fit);

// A chain candidate's description with its estimate: "xs_rear reads 0.8012 +- 0.0031 times the structure's motion
// (...)", naming a unit mix-up when the factor is one (mm read as m, g as m/s^2, and back), a reversed sign, or
// (`size_confounded`) that only the sign is known. `otherwise` when the candidate has more than one new parameter.
std::string chain_description(const Extension& ext, const FitResult& fit, const std::string& otherwise,
                              bool size_confounded);

// What extension `ext` says at the fit `s` of a model that contains it (`evaluator`): a chain candidate's
// chain_description at that fit, `otherwise` for the rest.
std::string described_at(const Extension& ext, const mbgen::Model& evaluator, const ModelState& s,
                         const std::string& otherwise);

// Delta BIC against the current model `base`, and whether the evidence is strong: BIC, validation and plausibility
// (DiagnoseOptions::min_delta_bic, min_validation_gain).
void rank_against(const ModelState& base, const DiagnoseOptions& options, CandidateOutcome& o);

// The outcome of a fitted candidate (its state `s`, its model derived as `evaluator`) against the current model
// `base`: plausibility (new parameters identifiable, determined, off their bounds; a new body's resonance shown by
// the data), its description, and its rank.
CandidateOutcome judge(const Extension& ext, const Model& evaluator, const ModelState& s, const ModelState& base,
                       int round, const DiagnoseOptions& options);

// The variants of one candidate (consecutive, one id) are one candidate: the one with the lowest BIC stands
// for it; those that fit exactly as well (a mirror-symmetric element, which the data cannot tell apart) are
// named with it. `states` are the outcomes' states, kept in step.
void keep_best_variants(std::vector<CandidateOutcome>& outcomes, std::vector<ModelState>& states);

// Ids of the other qualifying candidates that fit exactly as well as `best` (equivalent extensions).
std::vector<std::string> equivalents(const std::vector<CandidateOutcome>& outcomes, int best);

}  // namespace mbgen::diagnosis
