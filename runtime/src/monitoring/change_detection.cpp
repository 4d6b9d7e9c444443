// CUSUM design and update, baseline scatter (runtime/include/mbgen/change_detection.hpp, docs/monitor.md).
#include "mbgen/change_detection.hpp"

#include <algorithm>
#include <cmath>
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
  if (upper_ > h_ && upper_ >= lower_) return 1;
  if (lower_ > h_) return -1;
  return 0;
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

}  // namespace mbgen
