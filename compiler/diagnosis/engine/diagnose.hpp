// `mbgen diagnose`: show what a model's simulation gets wrong, name the cause, extend the model, measure the gain.
//
//   1. Fit the nominal model on the fit part of the data (data_split.hpp) and score it on the held-back part.
//   2. Compare measured and model FRFs against the noise level: the discrepancies (residual_analysis.hpp).
//   3. Enumerate candidate extensions from the model's own structure (extension.hpp), fit each (new parameters
//      started where the residual points, e.g. a new mode at an unexplained peak) and score it: BIC, validation
//      error, physical plausibility.
//   4. Select the best candidate only on strong evidence: BIC lower by more than 10 (Kass & Raftery's "very
//      strong"), validation error lower, new parameters plausible (identifiable, well determined, off their
//      bounds), and the discrepancy explained (the excess of the residual over the noise level at least halves).
//      Repeat with every candidate on the extended model (greedy forward selection) while it still shows a finding.
//      The measurement chain's candidates (a sensor's calibration or polarity, swapped cables, the force's) take part
//      in every round, fitted where a cheap statistic supports them (chain_scores.hpp). The extended model
//      must end near the noise level (mean normalized residual at most 3) and keep at most a third of the nominal
//      model's findings, or nothing is selected.
//   5. Verdict: `extended`; `no_extension_justified` when nothing beyond noise remains; `unexplained` when a clear
//      discrepancy remains that no candidate explains. A confident wrong extension is the worst outcome, so every
//      rule above errs towards `unexplained`.
#pragma once

#include <mbgen/estimation/fit.hpp>
#include <mbgen/residuals/residual_analysis.hpp>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "diagnosis/extension.hpp"
#include "ir/model_ir.hpp"

namespace mbgen::diagnosis {

struct DiagnoseOptions {
  std::map<std::string, std::string> set;  // --set overrides (decimal text)
  FitOptions fit;                          // the nominal fit (starts, seed, threads, weighting)
  // The nominal fit also starts where the model's modes match the data's own (mbgen/methods/modal_start.hpp): for
  // priors so far off that the search from them misses every mode, whose findings would be the fit's, not the
  // model's. One start more; the cost decides.
  bool start_from_modes = true;
  int candidate_starts = 2;                // starts per search of a candidate (start 0: the search's centre)
  // Screening: every candidate is first fitted more cheaply (two local fits, from the current estimate and from
  // the priors, without random starts, validation or residual analysis, on FRFs: the measured ones or the records'
  // H1 estimates; with records also three Gauss-Newton steps on the records); only the `full_fits` best by
  // screened BIC get the full two-search fit and a verdict. 0: every candidate is fitted fully. Four: in the test
  // cases and draw sweeps the candidate taken ranked first, second or third in the screening (docs/diagnosis.md,
  // step 5); the fourth place is the margin.
  int full_fits = 4;
  // A candidate's fits (screening and full) stop once their last 20 accepted steps together lowered n ln(cost), the
  // measure BIC compares models by, by less than this (FitOptions::stall_gain): far below the evidence a candidate
  // needs (|min_delta_bic|) and the rank changes screening looks for. The candidate taken is then fitted on to full
  // convergence before it is judged and the next round starts from it. 0: candidates' fits run to the full tolerance.
  // Not with time records (FitContext::candidate_stall_gain).
  double candidate_stall_gain = 0.1;
  double min_delta_bic = -10.0;
  double min_validation_gain = 0.01;       // relative decrease of the validation error required
  int max_extensions = 3;
  double max_final_residual = 3.0;         // mean normalized residual the extended model must reach (noise: 1)
  double max_remaining_findings = 1.0 / 3;  // fraction of the nominal model's findings the extended one may keep
  ResidualOptions residual;
  // The data the models are fitted on, when not all of it (`--fit-band`: the band a model is meant to represent);
  // the findings are judged over all the data either way. Same data sets, in the same order.
  std::optional<std::vector<DataSet>> fit_data;
  std::function<void(const std::string&)> progress;  // one line per step
};

struct CandidateOutcome {
  std::string id, description;
  std::string operator_name, target;  // Extension's: the id's two parts
  // For a candidate with variants (Extension::variant): the one reported (the lowest BIC), and the others that
  // fit exactly as well (within 0.01 in BIC), which the data cannot tell from it.
  std::string variant;
  std::vector<std::string> equivalent_variants;
  int variants_tried = 1;
  int round = 1;
  std::vector<NewParameter> new_parameters;
  std::vector<std::string> freed_parameters;
  // New parameters the data could not determine, held at their start values (the operator's physical guess) in
  // the fit that was judged: an engineer fixes what the data do not see and judges the rest.
  std::vector<std::string> held_parameters;
  FitResult fit;
  double validation_nrmse = 0;
  double delta_bic = 0;
  bool plausible = false;
  std::vector<std::string> doubts;  // why it is not plausible
  bool qualifies = false;           // strong evidence by BIC, validation and plausibility
  std::string error;                // it could not be derived or fitted
  double screen_delta_bic = 0;      // the screening fit's BIC minus the current model's on the same data
  double screen_records_delta_bic = 0;  // with time records: the same for the few steps on the records
  bool fully_fitted = true;         // false: screened out (its fit is the screening fit; it cannot qualify)
};

// One model with its fit and judgement: the nominal, then each accepted extension.
struct ModelState {
  ir::ModelIr model;
  std::string text;  // its .mdl text
  ModelInfo info;    // parameters with bounds, signals
  FitResult fit;
  std::map<std::string, double> values;  // fitted values of all its parameters, by name
  double validation_nrmse = 0;
  std::vector<ChannelResidual> channels;  // measured vs this model, for plots
  ResidualSummary residual;
  // Parameters the model declares `estimate` but its fit held at their values (CandidateOutcome::held_parameters);
  // they become `known` in `model` and `text` when the model is taken.
  std::vector<std::string> held;
};

struct DiagnosisResult {
  std::string model_file;
  unsigned long long seed = 1;  // DiagnoseOptions::fit.seed, the searches' seed
  std::string start_method;     // the estimation method whose estimate started the nominal fit (--method); "" none
  std::vector<std::string> warnings;  // the data checks' (the command's: a driving point with the wrong sign)
  std::vector<std::string> data;
  ModelState nominal;
  std::vector<CandidateOutcome> candidates;  // every round
  std::vector<std::string> selected;
  std::vector<std::string> selected_variants;  // the variant taken of each (same order); "" for one without variants
  // Per selected extension (same order): the nominal model's findings (indices into nominal.residual.discrepancies)
  // that the model shows before that extension is taken and no longer shows after it: what that effect explains.
  std::vector<std::vector<std::size_t>> explains;
  // Per selected extension (same order): what it says at the final model's estimates (a calibration factor's value
  // and std from the final fit; the round that took it fitted it beside effects not named yet: a miscalibrated
  // xs_rear with a loose mount and an added mass read 0.704 there and 0.799 in the final model, for 0.8).
  std::vector<std::string> described;
  // Extensions taken in a round and dropped again because the one taken after them does their work (backward
  // elimination, docs/diagnosis.md step 7): without them the final model's BIC rose by `bic_rise`, less than a round
  // needs.
  struct Superseded {
    std::string id, variant;
    int round = 0;
    double bic_rise = 0;
  };
  std::vector<Superseded> superseded;
  std::string verdict;  // "extended", "no_extension_justified", "unexplained"
  ModelState final;     // the extended model when extended, else the nominal
};

// The outcome of selected extension `id`: the last qualifying one of that id (the round it was taken in); null if
// none.
const CandidateOutcome* selected_outcome(const DiagnosisResult& result, const std::string& id);

DiagnosisResult diagnose(const ir::ModelIr& model, const std::string& model_text, const std::vector<DataSet>& data,
                         const DiagnoseOptions& options);

}  // namespace mbgen::diagnosis
