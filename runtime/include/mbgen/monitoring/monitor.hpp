// Monitoring one machine measured again and again (docs/monitor.md):
//
//   MonitorResult r = mbgen::monitor(model, data, options);   // data in time order
//
// 1. Each data set is fitted with fit() (fit.hpp): the first cold (FitOptions as given), every later one warm,
//    started at the previous estimate and at the cold priors, with fewer random starts.
// 2. The first `baseline` sets are the baseline: each parameter's level and scatter (change_detection.hpp: the
//    larger of the sets' spread and the fits' std), and the level of misfit a healthy machine shows.
// 3. From then on, each parameter's standardized shift from its reference level feeds a two-sided CUSUM whose
//    threshold gives one false alarm in `run_length` data sets for the whole scheme. An alarm is a change: it names
//    the parameters whose CUSUM crossed, with the estimated onset; the reference levels are then learned afresh
//    from the detecting set on, so a change that persists is reported once. A set without a change joins the
//    reference it was tested against (a self-starting CUSUM).
// 4. A set whose misfit after its fit (MonitorOptions::misfit) stands `structural_ratio` times above the baseline's
//    is a structural change: no parameter of the model explains it. Reported once, when it starts.
#pragma once

#include "mbgen/estimation/fit.hpp"

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mbgen {

struct MonitorProgress {
  int index = 0, count = 0;  // the data set being fitted (from 0) and how many there are
  std::string file;
  std::string stage;  // "fitting", or after the fit: the line of the set's outcome
};

struct MonitorOptions {
  int baseline = 3;   // the first sets, >= 2: their spread is the scatter the test is measured against
  FitOptions fit;     // the first set's fit (and the template of the warm ones)
  int warm_starts = 4;  // starts of the later fits: the previous estimate, the cold priors, 2 random
  // The CUSUM: reference value k = reference_shift / 2, tuned to shifts of `reference_shift` sigmas, and the
  // threshold for one false alarm in `run_length` data sets on average over all monitored parameters together.
  double reference_shift = 1.0;
  double run_length = 1000;
  // Structural change: a set's misfit above structural_ratio times the largest of the baseline's. The state ends
  // (and a later rise is a new change) only when the misfit falls below halfway, 1 + (structural_ratio - 1) / 2
  // times the baseline's: a hysteresis, so that a misfit hovering at the threshold is reported once.
  double structural_ratio = 1.25;
  // A set's misfit, larger when the model explains the data worse. Default (empty): the fit's residual variance
  // RSS/(n - k). `mbgen monitor` takes the mean normalized residual of the diagnosis's residual analysis instead
  // (residual against a noise level estimated from the data set itself).
  std::function<double(const DataSet&, const FitResult&)> misfit;
  // Called with each data set and its fit's options before the fit: may add starts (`mbgen monitor --method`: another
  // estimation method's estimate on that set). Empty: the starts above only.
  std::function<void(const DataSet&, FitOptions&)> add_starts;
  std::function<void(const MonitorProgress&)> progress;
};

// One data set's fit and where it stands.
struct MonitorPoint {
  std::string file;
  std::optional<std::string> time;  // its `# time=` (as written), if any
  FitResult fit;
  double misfit = 0;
  // Per monitored parameter: the standardized shift from its reference level and the CUSUM's two sides after
  // this set (both 0 within the baseline, where nothing is tested).
  std::map<std::string, double> shift, cusum_up, cusum_down;
  std::map<std::string, double> reference;  // the reference level tested against (the mean of the sets it rests on)
  bool baseline = false;
};

struct MonitorChange {
  int index = 0;  // the data set where it was detected
  int onset = 0;  // its estimated first data set (CUSUM change point; = index for a structural change alone)
  std::optional<std::string> time;
  std::vector<std::string> parameters;  // those that moved, in model order
  std::map<std::string, int> direction;  // +1 up, -1 down
  bool structural = false;
  double misfit_ratio = 0;  // the set's misfit over the baseline's largest
  // For a structural change (filled by callers that run the diagnosis): `cause` the extension the diagnosis
  // selected. When it selected none, `qualified` lists the candidates that qualified on their own (strong evidence
  // by BIC, validation and plausibility; lowest BIC first) but that the diagnosis's final checks did not confirm:
  // leads, not a cause (on the step-then-loose-wall test series the lowest BIC was a wrong one).
  std::string cause;
  std::vector<std::string> qualified;
  std::string text;
};

// The baseline's learned level and scatter of one parameter.
struct MonitoredParameter {
  std::string name, unit;
  double mean = 0, sigma = 0, sample_std = 0, fit_std = 0;
};

struct MonitorResult {
  std::string model;
  std::string start_method;  // the method whose estimate on each set started its fit (MonitorOptions::add_starts); "" none
  int baseline = 0;
  double k = 0, h = 0, run_length = 0, structural_ratio = 0;
  double single_set_limit = 0;  // a single standardized shift beyond it alarms on its own
  std::vector<MonitoredParameter> parameters;  // the monitored ones (estimated and identifiable in the baseline)
  double baseline_misfit = 0;                  // the largest misfit among the baseline sets
  std::vector<MonitorPoint> series;
  std::vector<MonitorChange> changes;
};

// Throws FitError when there are fewer than baseline + 1 data sets, baseline < 2, or no parameter can be monitored.
MonitorResult monitor(const Model& model, const std::vector<DataSet>& data,
                      const std::vector<std::optional<std::string>>& times, const MonitorOptions& options = {});

}  // namespace mbgen
