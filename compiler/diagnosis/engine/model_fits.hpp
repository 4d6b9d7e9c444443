// model_fits -- how the diagnosis fits a model to its data and measures it (the nominal model, each candidate, the
// refits): the fit on the fit part of the data, the validation error on the held-back part, the residual against
// the noise and the findings. A FitContext holds the data, the options and what candidates are screened on (the
// measured FRFs, or the records' H1 estimates), and passes the fits' progress to the caller one line at a time.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <mbgen/residuals/data_split.hpp>
#include <mbgen/dynamics/parallel.hpp>

#include "diagnosis/engine/diagnose.hpp"

namespace mbgen::diagnosis {

// Where a fit runs: on `threads` workers of its own, or (`cores` set) on its caller's thread and the free cores of
// a budget it shares with the fits beside it (a round's candidates: the core that finished the short ones joins
// the starts of the long one).
// `memo`: the local fits of this model already run (FitOptions::memo), shared by a candidate's screening and full
// fits, which start from the same points.
struct Workers {
  int threads = 1;
  std::shared_ptr<ThreadBudget> cores;
  std::shared_ptr<estimation::LocalFitMemo> memo;
  double stall_gain = 0;  // FitOptions::stall_gain: a candidate's fit (DiagnoseOptions::candidate_stall_gain)
};

// A model's parameter values by name (`values` in the order of info.parameters).
std::map<std::string, double> values_by_name(const ModelInfo& info, const Eigen::VectorXd& values);

// The values of `values` that model `info` estimates: start values for its fit. Its known and fixed parameters keep
// their own (another model's estimate of a parameter this one holds fixed must not leak into it).
std::map<std::string, double> estimated_values(const ModelInfo& info, const std::map<std::string, double>& values);

// The state of a twin candidate, carried over to `ext`: its model, and its parameters' names by position.
ModelState renamed(const ModelState& twin, const Extension& ext, const ModelInfo& info);

class FitContext {
 public:
  FitContext(const std::vector<DataSet>& data, const DiagnoseOptions& options);

  const std::vector<DataSet>& data() const { return data_; }
  const DiagnoseOptions& options() const { return options_; }
  // The fit part of the data (the held-back part judges validation).
  const std::vector<DataSet>& fit_data() const { return split_.fit; }
  bool has_records() const { return has_records_; }
  // What candidates are screened on, and the segments its FRFs average (their coherence's weighting).
  const std::vector<DataSet>& screen_data() const { return screen_data_; }
  int screen_averages() const { return screen_averages_; }
  bool screen_on_companion() const { return screen_on_companion_; }
  // With records: screen on the records' H1 estimates (estimation/spectral_companion.hpp) from now on.
  void screen_on_h1(std::vector<DataSet> h1, int averages);

  // DiagnoseOptions::candidate_stall_gain where it applies: 0 with time records. There a candidate's fit is
  // searched on the records' H1 estimates and refined on the records, and the stop made the spindle's 6 s base-mode
  // record slower (the on-feet base's fit 26 -> 48 s, the same result; 52-60 -> 84-94 s in all), not faster.
  double candidate_stall_gain() const { return has_records() ? 0.0 : options_.candidate_stall_gain; }

  // The options of a local fit from `from` (the values of it that model `info` estimates): the diagnosis's fit
  // options without their chosen starts, on one thread, without progress.
  FitOptions local_fit_options(const ModelInfo& info, const std::map<std::string, double>& from) const;

  // Derivation and tape compilation use GiNaC, which is not thread-safe: only ever on the calling thread.
  std::unique_ptr<Model> derive_model(const ir::ModelIr& model) const;

  // Fits `model` (parameters started at `start` where named) and judges it.
  ModelState assess(const ir::ModelIr& model, const std::string& text, const std::map<std::string, double>& start,
                    int starts) const;

  // The same with `model` already derived (`evaluator`), the fit on `workers`. Uses no GiNaC: safe on a worker
  // thread.
  // `held`: parameters with role estimate that this fit keeps at their values (the others are estimated).
  // `also_start_at`, `further_starts_at`, `optimum_start_at`: starts of the fit's search in addition to its
  // `starts`; `settle_first`: parameters held while the others settle from each start (FitOptions).
  ModelState assess(const Model& evaluator, const ir::ModelIr& model, const std::string& text,
                    const std::map<std::string, double>& start, int starts, const Workers& workers,
                    const std::map<std::string, double>& also_start_at = {}, const std::vector<std::string>& held = {},
                    const std::vector<std::map<std::string, double>>& further_starts_at = {},
                    const std::map<std::string, double>& optimum_start_at = {},
                    const std::vector<std::string>& settle_first = {}) const;

  // With records: whether a model, fitted on the records' H1 estimates from `start` (another model's estimates),
  // ends lower there in BIC than fitted from its own estimate `own`. A better optimum shows on the H1 as well, where
  // a fit costs milliseconds; only then is the model refitted on the records, where a model that misses an effect
  // crawls (a spindle without its base: 835 record iterations, 27 s, for a BIC 2 lower). True without a companion:
  // the refit itself is the test. `held`: estimated parameters kept at their values, as in assess().
  bool leads_lower_on_companion(const Model& evaluator, const std::vector<std::string>& held,
                                const std::map<std::string, double>& start,
                                const std::map<std::string, double>& own) const;

  // With records: the BIC of a model fitted on the records' H1 estimates from `start` (one local fit, `held` as in
  // assess()); none without a companion or where that fit fails.
  std::optional<double> bic_on_companion(const Model& evaluator, const std::vector<std::string>& held,
                                         const std::map<std::string, double>& start) const;

  // One progress line, under the fits' progress lock: a candidate's line may come while another candidate's fit
  // reports progress.
  void say(const std::string& line) const;

 private:
  const std::vector<DataSet>& data_;
  const DiagnoseOptions& options_;
  SplitData split_;
  bool has_records_;  // some data set is a time record
  std::vector<DataSet> screen_data_;
  int screen_averages_ = 1;
  bool screen_on_companion_ = false;
  mutable std::mutex fit_progress_mutex_;
};

}  // namespace mbgen::diagnosis
