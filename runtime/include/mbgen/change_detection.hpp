// Sequential detection of a shift in a stream of standardized values (docs/monitor.md): a two-sided CUSUM
// (Page 1954) with its threshold chosen for a stated in-control average run length (Siegmund's approximation), and
// the scatter of a monitored parameter learned from baseline data sets.
#pragma once

#include <vector>

namespace mbgen {

// The in-control average run length (data sets until a false alarm) of a one-sided CUSUM
//   S_n = max(0, S_{n-1} + z_n - k),  alarm when S_n > h,
// for standard normal z, by Siegmund's approximation: (exp(2 k b) - 2 k b - 1) / (2 k^2), b = h + 1.166.
// Within a few percent of the exact value (Markov chain) for k in [0.25, 1] and h >= 2.
double cusum_run_length(double k, double h);

// The threshold h for which cusum_run_length(k, h) equals `run_length` (> 1), by bisection.
double cusum_threshold(double k, double run_length);

// The threshold of a scheme of `streams` two-sided CUSUMs (one per monitored parameter) whose false alarms come
// on average once in `run_length` data sets: each of its 2 streams one-sided statistics gets run length
// 2 streams run_length (false alarms are rare events whose rates add).
double scheme_threshold(double k, double run_length, int streams);

// Page's two-sided CUSUM on standardized values. Also remembers where each side last stood at zero: the data set
// after it is the change point's maximum-likelihood estimate once that side alarms.
class TwoSidedCusum {
 public:
  TwoSidedCusum(double k, double h) : k_(k), h_(h) {}
  // Adds the value of data set `index`. Returns +1 when the upper side alarms (an increase), -1 for the lower side,
  // 0 otherwise.
  int update(double z, int index);
  void reset(int index);  // start afresh after data set `index`
  double upper() const { return upper_; }
  double lower() const { return lower_; }  // >= 0: the statistic of a decrease
  // The estimated first data set of the shift that side alarms on.
  int onset(int direction) const { return direction > 0 ? upper_zero_ + 1 : lower_zero_ + 1; }

 private:
  double k_, h_;
  double upper_ = 0, lower_ = 0;
  int upper_zero_ = -1, lower_zero_ = -1;
};

// The change point of a shift of unknown size in several streams of standardized values at once: `z[p][s]` for
// stream p and data set s (0 = the first set that could be changed, the last = the set of the alarm; NaN: no value,
// counts as 0). Returns the first changed set, argmax over t of sum_p (sum_{s >= t} z[p][s])^2 / (n - t), the
// generalized likelihood ratio's estimate (Lai 1995). The CUSUM's own estimate (TwoSidedCusum::onset) uses the
// reference shift k instead of the shift's size and moves the onset earlier when the sets before a large change
// happen to lie on its side (mdof2: two sets 1 sigma low before a 470-sigma step put it two sets early).
int change_point(const std::vector<std::vector<double>>& z);

// A parameter's level and scatter learned from baseline data sets: `values` are its estimates, `stds` the fits'
// standard deviations. sigma = max(sample standard deviation of the values, root mean square of the stds): the
// spread the data sets really show, but never below what each fit claims (a sample std from three sets is itself
// uncertain by ~50 %, and can by chance come out far too small).
struct BaselineScatter {
  double mean = 0;
  double sample_std = 0;  // of the values (n - 1 in the denominator); 0 for one value
  double fit_std = 0;     // root mean square of the fits' stds
  double sigma = 0;       // the scatter used: the larger of the two
  int count = 0;
};
BaselineScatter baseline_scatter(const std::vector<double>& values, const std::vector<double>& stds);

// The standardized shift of a new estimate x (its own fit's std `std`) from a reference mean of `count` estimates
// with scatter `sigma`: (x - mean) / sqrt(max(sigma, std)^2 + sigma^2 / count). The second term is the reference
// mean's own uncertainty.
double standardized_shift(double x, double std, double mean, double sigma, int count);

}  // namespace mbgen
