// Monitoring a machine in operation from output-only records (docs/monitor.md, "Monitoring in operation"):
//
//   OperationalMonitorResult r = mbgen::monitor_operational(sets, condition_names, options);
//
// 1. Each data set's modes come from output-only identification (output_only_modal.hpp, SSI-cov); the modes of
//    the first baseline set are the tracked ones, and every set's modes are paired with them by MAC (one to one,
//    largest MAC first, within a frequency window). A tracked mode must be found in every baseline set.
// 2. The features are the tracked modes' frequencies. Their dependence on the conditions (temperature, speed:
//    `# condition name=value` lines, condition.hpp) is learnt on the baseline and removed: a linear regression on
//    the measured variables, or where none is given a principal-component model of the baseline's features whose
//    leading components are taken as the environmental ones and projected out.
// 3. Each set's compensated features give a Hotelling T^2 against the baseline's residual covariance, divided by
//    the prediction's inflation 1 + h (h the set's leverage), so that without a change it is distributed as
//    nu p / (nu - p + 1) F(p, nu - p + 1) (p features, nu the residuals' degrees of freedom): the control limit is
//    that distribution's 1 - alpha quantile, alpha the false-alarm probability per set.
// 4. A run of alarmed sets is a change: it starts at its first set and names the modes whose compensated shift
//    stands out on its own (Student t, Bonferroni over the features).
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "mbgen/modal_identification/output_only_modal.hpp"

namespace mbgen {

// One data set as the monitor sees it: where it came from, its conditions and its identified modes.
struct OperationalSet {
  std::string file;
  std::optional<std::string> time;   // its `# time=` line, if any
  std::vector<double> conditions;    // in the order of the monitor's condition names
  std::vector<OperationalMode> modes;
};

enum class Compensation { Regression, PrincipalComponents, None };
const char* compensation_name(Compensation c);  // "regression", "principal components", "none"

struct OperationalMonitorOptions {
  int baseline = 0;             // the first K sets; 0: half the sets (at least what the test needs)
  double false_alarm = 0.01;    // alpha: the probability that a set without a change alarms
  double min_mac = 0.8;         // a set's mode continues a tracked one only with at least this MAC ...
  double max_relative_shift = 0.2;  // ... and a frequency within this fraction of the tracked mode's
  // Without measured conditions: the leading principal components removed as environmental. -1: as many as it
  // takes for `environmental_variance` of the baseline's variance, at most p - 1.
  int environmental_components = -1;
  double environmental_variance = 0.9;
  bool compensate = true;  // false: the raw features (to see what the conditions alone do to the chart)
};

struct TrackedMode {
  double f_hz = 0, zeta = 0;  // means over the baseline
  double f_std_hz = 0;        // the frequency's spread over the baseline (n - 1), conditions included
  Eigen::VectorXcd shape;     // the first baseline set's (unit norm)
};

struct OperationalPoint {
  std::string file;
  std::optional<std::string> time;
  std::vector<double> conditions;
  bool baseline = false;
  int identified = 0;                     // modes identified in the set
  std::vector<double> f_hz, zeta, mac;    // per tracked mode; NaN where it was not found
  // Per tracked mode: the frequency with the conditions' effect removed (at the baseline's mean conditions; the
  // raw one without compensation), its shift from the prediction in per cent and in sigmas (the prediction's
  // uncertainty included); NaN where not found.
  std::vector<double> compensated_hz, shift_percent, shift_sigma;
  double leverage = 0;
  double t2 = 0;       // NaN when a tracked mode is missing (the set is not tested)
  bool alarm = false;  // t2 above the limit (after the baseline only)
};

struct OperationalChange {
  int index = 0;     // the set where it starts (its first alarm)
  int last = 0;      // the last set of the run of alarms
  std::vector<int> modes;  // tracked modes that moved (their shift beyond mode_limit at `index`)
  std::vector<double> shift_percent, shift_sigma;  // per tracked mode at `index`
  std::string text;
};

struct OperationalMonitorResult {
  std::vector<std::string> conditions;  // names
  Compensation compensation = Compensation::Regression;
  int baseline = 0;
  double false_alarm = 0;
  int features = 0, dof = 0;  // p and nu of the T^2 limit
  double limit = 0;           // the T^2 control limit
  double mode_limit = 0;      // |shift_sigma| above this names a mode as moved (t_nu, two-sided, alpha / p)
  int environmental_components = 0;       // principal components removed
  std::vector<double> component_variance; // principal components only: each one's fraction of the variance
  // Regression: per tracked mode, the frequency's change per unit of each condition (Hz per unit), in condition
  // order; principal components: the removed directions (per component, per mode, unit length in Hz).
  std::vector<std::vector<double>> effects;
  std::vector<double> residual_std_hz;  // per tracked mode, of the baseline's compensated residuals
  std::vector<TrackedMode> modes;
  std::vector<OperationalPoint> series;
  std::vector<OperationalChange> changes;
  // For explaining a change by a model: the projection (tracked modes x tracked modes) the compensation applies
  // to a shift (identity for regression and none, the minor principal components' projector otherwise).
  Eigen::MatrixXd shift_projector;
};

// Throws std::invalid_argument when: there are no more sets than the baseline, the first baseline set has no mode,
// no tracked mode is found in every baseline set, or the baseline is too small for the test (K >= p + q + 2 with q
// the condition variables, p the tracked modes; with principal components K >= p + 1).
OperationalMonitorResult monitor_operational(const std::vector<OperationalSet>& sets,
                                             const std::vector<std::string>& condition_names,
                                             const OperationalMonitorOptions& options = {});

// P(F <= x) for Fisher's F with d1, d2 > 0 degrees of freedom, and its quantile (bisection, 1e-12 relative).
double f_distribution_cdf(double x, double d1, double d2);
double f_distribution_quantile(double p, double d1, double d2);

// The T^2 control limit for p features against residuals with nu >= p degrees of freedom:
// nu p / (nu - p + 1) F_(1 - alpha)(p, nu - p + 1).
double hotelling_limit(int p, int nu, double alpha);

}  // namespace mbgen
