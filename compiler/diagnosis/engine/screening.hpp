// screening -- the cheap fits that decide which of a round's candidates are fitted fully (docs/diagnosis.md,
// "Screening").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "diagnosis/engine/model_fits.hpp"

namespace mbgen::diagnosis {

// One candidate's screening fits: its BIC in each ranking (on the FRFs; with time records also on the records),
// +inf where a ranking has no evidence from it, and its fit on the FRFs.
struct ScreeningFit {
  std::vector<double> bic;
  ModelState state;   // the fit on the FRFs, as the candidate's state
  std::string error;  // the fit on the FRFs failed: the candidate has failed
};

// Screening (DiagnoseOptions::full_fits): cheaper fits of every candidate, ranked by BIC against the current
// model fitted the same way; candidates outside the `full_fits` best are screened out: their outcome is the
// screening fit, and they cannot qualify.
//  - On FRFs (the measured ones, or the records' H1 estimates: no simulation): a candidate that contains the
//    current model (Extension::nesting) descends from the point where it is the current model, once, to
//    convergence (the score test carried through); any other, two local fits to convergence, from the current
//    estimate and from the priors (the centres of the full fit's two searches, without its random starts,
//    validation or residual analysis), and one from each of the candidate's alternative starts.
//  - With time records also a few Gauss-Newton steps on the records from the current estimate: an effect the
//    records show but their H1 estimates' coarse lines blur (the gyroscopic split of the spindle's modes at
//    300 rev/s, a few Hz under 8 Hz lines: screening delta BIC +17.9 on the H1 estimates, -20681 fitted on the
//    records) shows in the time-domain cost at once. The kept candidates alternate between the two rankings.
// The fits of candidates are independent of each other (fit() runs on any thread, several at once: a round screens
// its first candidates while the later ones are still being derived); select() ranks them once all have run.
class Screening {
 public:
  // Whether a round of `candidates` models is screened at all: full_fits > 0 and fewer places than candidates.
  static bool applies(const FitContext& fits, std::size_t candidates);

  // Derives the current model where the records' ranking needs it: on the calling thread (GiNaC). `cores`: the
  // budget the screening fits' starts share.
  Screening(const FitContext& fits, const ModelState& base, std::shared_ptr<ThreadBudget> cores);

  // The current model fitted the same way, for each ranking: once, before select(), on any thread.
  void fit_base();

  // A candidate's screening fits; `memo`: its local-fit memo, which its full fit shares.
  ScreeningFit fit(const Extension& ext, const Model& evaluator,
                   const std::shared_ptr<estimation::LocalFitMemo>& memo) const;

  // Ranks `fitted` (the candidates fitted in their own right) by `screened[k]`, their screening fits: fills
  // `screen_delta_bic` of each, puts each candidate's screening fit in `states[k]`, and sets `screened_out[k]` (with
  // its outcome, the screening fit's) for those not kept, and for those whose screening fit on the FRFs failed.
  void select(const std::vector<Extension>& extensions, const std::vector<std::size_t>& fitted, int round,
              std::vector<ScreeningFit>& screened, std::vector<CandidateOutcome>& outcomes,
              std::vector<ModelState>& states, std::vector<char>& screened_out) const;

 private:
  enum class Kind { Spectral, Records };
  FitResult fit_as(const Model& evaluator, const Extension* ext, Kind kind,
                   const std::shared_ptr<estimation::LocalFitMemo>& memo) const;

  const FitContext& fits_;
  const ModelState& base_;
  std::shared_ptr<ThreadBudget> cores_;
  std::vector<Kind> kinds_;
  std::unique_ptr<Model> base_model_;  // with records only
  std::vector<double> base_bic_, base_cost_;
};

}  // namespace mbgen::diagnosis
