// Output-error estimation of physical parameters from measured FRFs and time records (docs/estimation.md).
//
//   FitResult r = mbgen::fit(model, data, options);
//
// Frequency domain: residuals are model minus measured FRF at the measured frequencies, real and imaginary
// parts stacked, divided by the standard deviation of the measurement (from coherence, frf_sigma.hpp).
// Time domain (the thesis's "one step" method, Sec. 3.6.3): the model is simulated from rest with the
// record's inputs (zero-order hold, or first-order hold for `# hold=none`) and its outputs compared with the
// measured ones, each output channel divided by its measured RMS. Both use analytic Jacobians.
//
// Parameters with role Estimate are fitted (or the names in FitOptions::estimate); the others stay at their
// values. Bounds are enforced by reparameterisation (parameterization.hpp). The local solver is
// Levenberg-Marquardt; the global search is a deterministic multi-start over std::thread workers. Parameters
// the data cannot determine are reported identifiable = false and kept at their prior (identifiability.hpp).
#pragma once

#include "mbgen/data/data_set.hpp"
#include "mbgen/data/frf_data.hpp"
#include "mbgen/data/frf_sigma.hpp"  // FrfWeighting: the FRF residuals' standard deviation
#include "mbgen/dynamics/model_modes.hpp"
#include "mbgen/model.hpp"
#include "mbgen/dynamics/parallel.hpp"
#include "mbgen/estimation/residual_tests.hpp"
#include "mbgen/data/time_record.hpp"
#include "mbgen/estimation/validation_fit.hpp"

#include <Eigen/Core>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mbgen {

namespace estimation {
class LocalFitMemo;
}

// An empty memo of local fits (FitOptions::memo).
std::shared_ptr<estimation::LocalFitMemo> make_local_fit_memo();

// Bad fit input (unknown channel or parameter names, empty data, ...). what() names the file where known.
class FitError : public std::runtime_error {
 public:
  explicit FitError(const std::string& what) : std::runtime_error(what) {}
};

struct FitProgress {
  int start = 0;       // index of the start being refined (0 = the prior)
  int starts = 1;      // number of starts in this stage
  int iteration = 0;   // LM iteration within that start
  double cost = 0;     // weighted residual sum of squares
  std::string stage;   // "settle", "search", "refine", "refine records" (time records), "final"
};

struct FitOptions {
  // Parameters to estimate; empty: those with role Estimate. Known/Fixed parameters named here are estimated too.
  std::vector<std::string> estimate;
  // Parameter values overriding the model's defaults (the command line's --set); they are also the priors.
  std::map<std::string, double> values;

  // Global search: `starts` local fits (start 0 at the prior, the others (but see also_start_at and
  // further_starts_at) drawn log-uniformly within a factor
  // `spread` of the prior, clipped to the bounds) from a std::mt19937_64 seeded with `seed`; the best final cost
  // wins, ties to the lower start index, so the result does not depend on thread timing.
  int starts = 16;
  // A second start of one's choosing (values by name; parameters not named start at the prior): start 1, before
  // the random ones, when `starts` > 1. E.g. a diagnosis candidate searched around the current estimate and
  // also from the model's defaults, in one search.
  std::map<std::string, double> also_start_at;
  // A start at (or next to) an optimum of the weighted cost already, e.g. a diagnosis candidate where it is the
  // current model again (its new element switched off, the rest at the current estimate): the start after
  // also_start_at, refined on the weighted residuals directly. The log-ratio search (log_search), whose optimum
  // differs from the weighted one, would lead it away: from such starts on a spindle base on feet fitted to the
  // noise level, every candidate's search ended 16 000 to 31 000 BIC units above the current model it contains.
  std::map<std::string, double> optimum_start_at;
  // More starts of one's choosing, in this order after also_start_at and before the random ones, each while
  // `starts` allows (named values; the others at the prior). E.g. a diagnosis candidate's new mode started at
  // each of the data's unexplained peaks, not only at the strongest.
  std::vector<std::map<std::string, double>> further_starts_at;
  // Parameters held at their start values while the other free ones settle around them (the start's search and
  // refinement on those alone), before all are refined together: from the starts where the parameters not named
  // stand at the prior (`values`), that is start 0 and further_starts_at. E.g. a diagnosis candidate's new
  // structural element fitted around the current estimate, which has absorbed part of what the element explains (a
  // rigid wall's spring holds the series stiffness of the wall's support and itself): with the element added at
  // its start the model's own modes stand misplaced, and a joint fit switched the element off (a wall damped rigid)
  // before it could place the new mode (docs/estimation.md, "Solver and global search").
  std::vector<std::string> settle_first;
  double spread = 3.0;
  unsigned long long seed = 1;
  // The search ends early once `agree` of its starts, counted in index order, have ended within a relative 1e-6 of
  // the lowest cost among them, and that cost is within 10 % of what the measurement noise alone would leave
  // (estimated from the data, frf_noise.hpp; FRF data and records searched on their H1 only): the best optimum,
  // found that often and leaving only noise, is taken as the global one (a frame3 fit reached its optimum from 13
  // of 16 starts). A model that misses something never stops early: its local optima are many, and several
  // starts may agree on one that is not the best. Which starts run depends only on their results, not on timing.
  // 0: every start runs.
  int agree = 3;
  int threads = 2;
  // When set, the starts run on the caller's thread and on whatever cores of this budget are free, shared with
  // other fits (`threads` is then not used): a diagnosis fits its candidates side by side on one budget.
  std::shared_ptr<ThreadBudget> cores;
  // FRF data: the starts are first fitted on log-ratio residuals log(H_model / H_measured), whose cost stays
  // informative when a lightly damped model peak misses the measured one; the best is then refined on the
  // statistically weighted complex residuals.
  bool log_search = true;
  // The log-ratio search stops once an accepted step lowers its cost by less than this fraction. A looser value
  // (1e-4: the search only has to reach a basin) saved ~40 % of a spindle global fit, but sent one of the 20
  // random-prior mdof2 runs to a wrong optimum; so by default the search converges as fully as the refinement.
  double search_cost_tolerance = 1e-10;
  // Time records: the starts are fitted on FRFs estimated from the records (Welch H1 with coherence, log-ratio
  // search then weighted refine), and only the best is refined on the records (one simulation-based local fit
  // instead of `starts`). Off: every start is fitted on the records.
  bool spectral_search = true;

  // Levenberg-Marquardt stopping rules.
  int max_iterations = 200;
  double cost_tolerance = 1e-10;  // relative decrease of the cost in an accepted step
  double step_tolerance = 1e-10;  // norm of the step in internal coordinates
  double gradient_tolerance = 1e-12;
  // A local fit still descending at max_iterations goes on while its last 50 accepted steps together lowered
  // n ln(cost) (n residuals: the measure BIC compares models by) by more than `continue_gain`, up to
  // `iteration_cap` iterations. 0: every fit stops at max_iterations.
  double continue_gain = 10;
  int iteration_cap = 1000;
  // A local fit whose last 20 accepted steps together lowered n ln(cost) by less than this stops there (0: off). For
  // fits that only compare models by BIC (a diagnosis's candidates): on the spindle most of their iterations were
  // such a crawl, gaining a few hundredths of a BIC unit in 190 steps.
  double stall_gain = 0;

  double zero_tolerance = 1e-10;  // identifiability: see identifiability.hpp
  double rank_tolerance = 1e-7;
  // Where a parameter the data cannot determine at the estimate is held while the rest are fitted again: at its
  // prior (reported there, the user's value), or where the search left it. At the estimate the refit starts at a
  // stationary point of the others and cannot end above the search's cost; back at the prior it moves the model, and
  // near the noise the refit crawled to its iteration limit and ended higher (a diagnosis's screening fits, which
  // only rank candidates by their cost, hold them at the estimate: docs/diagnosis.md, step 5).
  bool unidentifiable_to_prior = true;

  FrfWeighting frf_weighting;
  // Local fits already run (make_local_fit_memo()), shared by later fits of the same model: a search's start met
  // again takes the earlier result, which is bit-identical to what running it again would give (the key covers
  // the start, the prior, the bounds, the solver's options and the residuals there: local_fit_memo.hpp). Use one
  // memo per model. A diagnosis shares one between a candidate's screening fit and its full fits.
  std::shared_ptr<estimation::LocalFitMemo> memo;
  std::function<void(const FitProgress&)> progress;  // called from worker threads, one call at a time
};

struct ParameterEstimate {
  std::string name, unit;
  double prior = 0;
  double value = 0;
  double std = 0;             // standard deviation in physical units; 0 when not estimated
  bool estimated = false;     // a candidate that was fitted
  bool identifiable = true;   // false: the data cannot determine it (kept at the prior, or where the search left it:
                              // FitOptions::unidentifiable_to_prior), or it is at a bound
  // "lower" or "upper" when the optimum lies on that bound (the data pull the parameter beyond it): the value is the
  // bound, there is no std (a linearisation at a bound means nothing) and identifiable is false. Empty otherwise.
  std::string at_bound;
  std::vector<std::string> confounded_with;  // parameters it is not separable from (if any)
  // How much the fit would gain by moving this parameter alone beyond where it stands, in units of the residual
  // variance (chi-square): (r . J_p)^2 / (|J_p|^2 s^2) at the estimate. An interior optimum has zero gradient, so
  // this is near zero unless a bound holds the parameter; `toward` says which way the fit pulls (-1 lower, +1 higher).
  double pull_chi2 = 0;
  int toward = 0;
};

struct FitResult {
  std::string model;
  std::vector<std::string> data;  // data set file names
  std::string method;             // "frf-output-error", "time-output-error" or "mixed-output-error"

  std::vector<ParameterEstimate> parameters;  // the candidates for estimation, in model order
  Eigen::VectorXd prior_values;               // all model parameters
  Eigen::VectorXd values;                     // all model parameters at the estimate
  // Names of the identifiable, fitted ones not at a bound: the order of the matrices. The covariance treats
  // parameters at a bound as fixed there (an active constraint).
  std::vector<std::string> estimated;
  Eigen::MatrixXd covariance;                 // of `estimated`, physical units
  Eigen::MatrixXd correlation;
  Eigen::VectorXd singular_values;  // of the unit-column-scaled Jacobian of all candidates at the estimate

  long residual_count = 0;     // n: real residuals
  double cost = 0;             // weighted residual sum of squares at the estimate (RSS)
  double initial_cost = 0;     // at the prior
  double residual_variance = 0;  // RSS / (n - k)
  double nrmse = 0;            // sqrt(RSS / sum of squared weighted measurements)
  double bic = 0;              // n log(RSS / n) + k log n, k = the fitted parameters (those at a bound included)

  std::vector<Mode> modes;  // of the model at the estimate (without per-data-set values)

  // Results particular to the method that ran (docs/methods.md): member name -> a JSON text, written under
  // "method_details" in mbgen-fit/1. Empty for the output-error methods.
  std::map<std::string, std::string> method_details;

  int iterations = 0;                // LM iterations of the final refinement
  std::vector<double> cost_history;  // cost per accepted iteration: best start's search, then refinement
  std::vector<double> start_costs;   // final cost of every start run (FitOptions::agree may end the search early;
                                     // search stage; for time records, on their H1)
  int best_start = 0;
  bool converged = false;
  std::string stop_reason;
  unsigned long long seed = 1;  // FitOptions::seed of the search (recorded so a run can be repeated)
  // What a user must know before reading the estimates (the command's data checks, e.g. a driving point with the
  // wrong sign): the summary and the report open with them, the JSON has them under `warnings`.
  std::vector<std::string> warnings;
  // Filled by the caller after the fit (the command does, docs/estimation.md), empty otherwise: the residual tests
  // of the time records fitted (residual_tests.hpp), written under `residual_tests`; the scores on other data
  // (`fit --validate`, validation_fit.hpp), written under `validation`.
  std::vector<ChannelResidualTest> residual_tests;
  int residual_test_lags = 0;  // L asked for (a short record's tests use fewer: their lags say)
  std::vector<ValidationScore> validation;
};

FitResult fit(const Model& model, const std::vector<DataSet>& data, const FitOptions& options = {});

// Weighted residuals at the given full parameter vector (for reports and checks): r and, per data set, the
// model's predicted channels. `sum_squares_measured` is the weighted measurement norm nrmse divides by.
struct Prediction {
  // Per data set, per channel (FRF: channel order of the file; time: the model outputs present in the record),
  // the model's values (complex FRF, or real time signal in .real()).
  std::vector<std::vector<Eigen::VectorXcd>> channels;
  std::vector<std::vector<std::string>> channel_names;
};
Prediction predict(const Model& model, const std::vector<DataSet>& data, const Eigen::VectorXd& values);

}  // namespace mbgen
