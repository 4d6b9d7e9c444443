// CUSUM design and update, baseline scatter (runtime/include/mbgen/monitoring/change_detection.hpp, docs/monitor.md).
#include "mbgen/monitoring/change_detection.hpp"
#include "numerics/constants.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mbgen {

double cusum_run_length(double k, double h) {
  const double b = h + 1.166;  // Siegmund's correction for the overshoot of the boundary
  const double a = 2 * k * b;
  return (std::exp(a) - a - 1) / (2 * k * k);
}

double cusum_threshold(double k, double run_length) {
  if (!(k > 0) || !(run_length > 1)) throw std::invalid_argument("cusum_threshold: need k > 0 and a run length > 1");
  // The run length grows monotonically with h; bracket, then bisect.
  double lo = 0, hi = 1;
  while (cusum_run_length(k, hi) < run_length) hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (cusum_run_length(k, mid) < run_length ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double scheme_threshold(double k, double run_length, int streams) {
  if (streams < 1) throw std::invalid_argument("scheme_threshold: no stream to monitor");
  return cusum_threshold(k, 2.0 * streams * run_length);
}

int TwoSidedCusum::update(double z, int index) {
  upper_ = std::max(0.0, upper_ + z - k_);
  lower_ = std::max(0.0, lower_ - z - k_);
  if (upper_ == 0) upper_zero_ = index;
  if (lower_ == 0) lower_zero_ = index;
  if ((upper_ > h_ || z > limit_) && upper_ >= lower_) return 1;
  if (lower_ > h_ || z < -limit_) return -1;
  return 0;
}

double single_set_limit(double run_length, int streams) {
  if (streams < 1 || !(run_length > 1)) throw std::invalid_argument("single_set_limit: need streams and a run length > 1");
  return -normal_quantile(0.5 / (streams * run_length));
}

void TwoSidedCusum::reset(int index) {
  upper_ = lower_ = 0;
  upper_zero_ = lower_zero_ = index;
}

int change_point(const std::vector<std::vector<double>>& z) {
  std::size_t n = 0;
  for (const auto& stream : z) n = std::max(n, stream.size());
  int best = 0;
  double best_score = -1;
  for (std::size_t t = 0; t < n; ++t) {
    double score = 0;
    for (const auto& stream : z) {
      double sum = 0;
      for (std::size_t s = t; s < stream.size(); ++s)
        if (std::isfinite(stream[s])) sum += stream[s];
      score += sum * sum;
    }
    score /= static_cast<double>(n - t);
    if (score > best_score) {  // ties to the earlier set
      best_score = score;
      best = static_cast<int>(t);
    }
  }
  return best;
}

BaselineScatter baseline_scatter(const std::vector<double>& values, const std::vector<double>& stds) {
  BaselineScatter s;
  s.count = static_cast<int>(values.size());
  if (values.empty()) return s;
  for (double v : values) s.mean += v;
  s.mean /= static_cast<double>(values.size());
  if (values.size() > 1) {
    double ss = 0;
    for (double v : values) ss += (v - s.mean) * (v - s.mean);
    s.sample_std = std::sqrt(ss / static_cast<double>(values.size() - 1));
  }
  if (!stds.empty()) {
    double ss = 0;
    for (double v : stds) ss += v * v;
    s.fit_std = std::sqrt(ss / static_cast<double>(stds.size()));
  }
  s.sigma = std::max(s.sample_std, s.fit_std);
  return s;
}

double standardized_shift(double x, double std, double mean, double sigma, int count) {
  const double own = std::max(sigma, std);
  const double var = own * own + (count > 0 ? sigma * sigma / count : 0.0);
  return var > 0 ? (x - mean) / std::sqrt(var) : 0.0;
}

namespace {

// The continued fraction of the incomplete beta function (modified Lentz), for x < (a + 1) / (a + b + 2).
double beta_fraction(double a, double b, double x) {
  const double tiny = 1e-300;
  double c = 1, d = 1 - (a + b) * x / (a + 1);
  d = 1 / (std::abs(d) < tiny ? tiny : d);
  double h = d;
  for (int m = 1; m <= 500; ++m) {
    for (int half = 0; half < 2; ++half) {
      const double num = half == 0 ? m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m))
                                   : -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1));
      d = 1 + num * d;
      d = 1 / (std::abs(d) < tiny ? tiny : d);
      c = 1 + num / c;
      if (std::abs(c) < tiny) c = tiny;
      h *= d * c;
      if (half == 1 && std::abs(d * c - 1) < 1e-16) return h;
    }
  }
  return h;
}

// The regularized incomplete beta function I_x(a, b).
double incomplete_beta(double a, double b, double x) {
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) +
                                b * std::log1p(-x));
  if (x < (a + 1) / (a + b + 2)) return front * beta_fraction(a, b, x) / a;
  return 1 - front * beta_fraction(b, a, 1 - x) / b;
}

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

}  // namespace

double regularized_incomplete_beta(double a, double b, double x) { return incomplete_beta(a, b, x); }

double student_t_cdf(double t, double nu) {
  if (std::isinf(nu)) return normal_cdf(t);
  // P(|T| > |t|) = I_{nu / (nu + t^2)}(nu / 2, 1 / 2).
  const double tail = 0.5 * incomplete_beta(nu / 2, 0.5, nu / (nu + t * t));
  return t > 0 ? 1 - tail : tail;
}

double normal_quantile(double p) {
  if (!(p > 0) || !(p < 1)) throw std::invalid_argument("normal_quantile: p must lie in (0, 1)");
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double low = 0.02425;
  double x;
  if (p < low || p > 1 - low) {
    const double q = std::sqrt(-2 * std::log(p < low ? p : 1 - p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    if (p > 1 - low) x = -x;
  } else {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  }
  // One Halley step on Phi(x) - p.
  const double e = normal_cdf(x) - p;
  const double u = e * std::sqrt(numerics::kTwoPi) * std::exp(x * x / 2);
  return x - u / (1 + x * u / 2);
}

double t_to_normal(double t, double nu) {
  if (std::isinf(nu) || !std::isfinite(t)) return t;
  // The smaller tail, for accuracy far out: P(T > |t|), mapped to the normal value with that upper tail.
  const double tail = 0.5 * incomplete_beta(nu / 2, 0.5, nu / (nu + t * t));
  if (!(tail > 0)) return t;  // beyond double's range: keep the t, which is then far beyond any threshold
  const double z = -normal_quantile(std::min(tail, 0.5));
  return t < 0 ? -z : z;
}

SelfStartingReference::SelfStartingReference(const std::vector<double>& baseline, double fit_std) : fit_std_(fit_std) {
  if (baseline.size() < 2) throw std::invalid_argument("SelfStartingReference: the baseline needs two values");
  for (double v : baseline) join(v);
}

void SelfStartingReference::join(double x) {
  if (count_ == 0) {
    sum_ = x, count_ = 1;
    return;
  }
  const double before = mean();
  sum_ += x;
  ++count_;
  m2_ += (x - before) * (x - mean());  // Welford: the regime's squared deviations, pooled across regimes
  ++pooled_dof_;
}

void SelfStartingReference::restart(double x) {
  sum_ = x;
  count_ = 1;
}

double SelfStartingReference::sample_std() const { return pooled_dof_ > 0 ? std::sqrt(m2_ / pooled_dof_) : 0.0; }
double SelfStartingReference::sigma() const { return std::max(sample_std(), fit_std_); }
double SelfStartingReference::dof() const {
  return sample_std() >= fit_std_ && pooled_dof_ > 0 ? pooled_dof_ : std::numeric_limits<double>::infinity();
}

double SelfStartingReference::z(double x, double std) const {
  return t_to_normal(standardized_shift(x, std, mean(), sigma(), count_), dof());
}

}  // namespace mbgen
