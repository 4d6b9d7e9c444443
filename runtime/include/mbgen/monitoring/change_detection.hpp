// Sequential detection of a shift in a stream of standardized values (docs/monitor.md): a two-sided CUSUM
// (Page 1954) with its threshold chosen for a stated in-control average run length (Siegmund's approximation), and
// the scatter of a monitored parameter learned from baseline data sets.
#pragma once

#include <limits>
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

// The single-value limit of a scheme of `streams` two-sided tests whose single-value alarms alone come once in
// `run_length` data sets on average: |z| > limit with probability 1 / (streams run_length) per stream and set.
double single_set_limit(double run_length, int streams);

// Page's two-sided CUSUM on standardized values. Also remembers where each side last stood at zero: the data set
// after it is the change point's maximum-likelihood estimate once that side alarms.
class TwoSidedCusum {
 public:
  // `limit`: a single value beyond +-limit alarms on its own (a combined Shewhart-CUSUM scheme, Lucas 1982).
  TwoSidedCusum(double k, double h, double limit = std::numeric_limits<double>::infinity())
      : k_(k), h_(h), limit_(limit) {}
  // Adds the value of data set `index`. Returns +1 when the upper side alarms (an increase), -1 for the lower side,
  // 0 otherwise.
  int update(double z, int index);
  void reset(int index);  // start afresh after data set `index`
  double upper() const { return upper_; }
  double lower() const { return lower_; }  // >= 0: the statistic of a decrease
  // The estimated first data set of the shift that side alarms on.
  int onset(int direction) const { return direction > 0 ? upper_zero_ + 1 : lower_zero_ + 1; }

 private:
  double k_, h_, limit_;
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

// P(T <= t) for Student's t with nu > 0 degrees of freedom (the regularized incomplete beta function); nu = inf:
// the standard normal's.
double student_t_cdf(double t, double nu);

// The regularized incomplete beta function I_x(a, b), a, b > 0 (continued fraction, modified Lentz).
double regularized_incomplete_beta(double a, double b, double x);

// The standard normal quantile of p in (0, 1) (Acklam's rational approximation, refined by one Halley step: about
// 1e-15 relative).
double normal_quantile(double p);

// A value distributed as Student's t with nu degrees of freedom mapped to the standard normal value of the same tail
// probability (nu = inf: unchanged): what the CUSUM's threshold assumes. A shift standardized by a scatter estimated
// from few sets has the t's heavy tails; taken as normal, three baseline sets gave false alarms on ordinary day-to-day
// scatter (two in twelve daily mdof2 sets with 0.5 % scatter in the truth, against a stated one in 1000).
double t_to_normal(double t, double nu);

// One monitored parameter's reference level and scatter, learned self-starting (docs/monitor.md, "The sequential
// test"): the level from the sets of the current regime, the scatter pooled over every in-control set of every
// regime (their deviations from their own regime's level), never below the baseline fits' root mean square std.
// Its standardized shifts are independent and standard normal without a change, whatever the number of sets behind
// it (Hawkins 1987, self-starting CUSUM). A step's first sets, tested and not yet alarmed on, join and widen the
// scatter: the scheme's single-set limit (TwoSidedCusum) finds a large step at its first set.
class SelfStartingReference {
 public:
  // The baseline's estimates (at least 2) and the root mean square of their fits' stds.
  SelfStartingReference(const std::vector<double>& baseline, double fit_std);
  // The standardized shift of estimate x (its fit's std `std`) as a standard normal value: (x - mean) over
  // sqrt(max(sigma, std)^2 + sigma^2 / count), a Student t with the scatter's degrees of freedom where the sets'
  // spread sets sigma (normal where the fits' std does), mapped by t_to_normal.
  double z(double x, double std) const;
  void join(double x);     // a set tested without a change joins the level and the scatter
  void restart(double x);  // a change: the level from x alone, the scatter pooled on
  double mean() const { return sum_ / count_; }
  int count() const { return count_; }
  double sigma() const;      // the scatter used
  double sample_std() const;  // the sets' pooled spread
  double dof() const;        // the degrees of freedom behind sigma (infinite where the fits' std sets it)

 private:
  double sum_ = 0, m2_ = 0, fit_std_ = 0;
  int count_ = 0, pooled_dof_ = 0;
};

}  // namespace mbgen
