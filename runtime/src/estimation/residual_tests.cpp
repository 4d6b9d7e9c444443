// Whiteness of a record fit's residuals and their independence of the inputs (mbgen/estimation/residual_tests.hpp).
#include "mbgen/estimation/residual_tests.hpp"

#include "mbgen/estimation/fit.hpp"

#include <algorithm>
#include <cmath>

namespace mbgen {

namespace {

Eigen::VectorXd centred(const Eigen::VectorXd& x) { return x.array() - x.mean(); }

// sum_t a(t+k) b(t) over the samples where both exist.
double lagged_sum(const Eigen::VectorXd& a, const Eigen::VectorXd& b, int k) {
  const Eigen::Index n = a.size() - std::abs(k);
  if (n <= 0) return 0;
  return k >= 0 ? a.segment(k, n).dot(b.head(n)) : a.head(n).dot(b.segment(-k, n));
}

// Counts the judged lags outside the band (lag 0 of an autocorrelation is not judged: it is 1 by definition).
void judge(CorrelationTest& t, bool skip_lag_zero) {
  t.judged = t.outside = 0;
  for (std::size_t i = 0; i < t.lags.size(); ++i) {
    if (skip_lag_zero && t.lags[i] == 0) continue;
    ++t.judged;
    if (std::abs(t.values[i]) > t.band) ++t.outside;
  }
  t.allowed = allowed_outside(t.judged);
  // The per-lag band is kResidualBandQuantile sigma; the simultaneous one the Bonferroni quantile times the same sigma.
  t.simultaneous_band =
      t.judged > 0 ? t.band / kResidualBandQuantile * two_sided_normal_quantile(0.01 / t.judged) : t.band;
  t.beyond_simultaneous = 0;
  for (std::size_t i = 0; i < t.lags.size(); ++i)
    if (!(skip_lag_zero && t.lags[i] == 0) && std::abs(t.values[i]) > t.simultaneous_band) ++t.beyond_simultaneous;
}

}  // namespace

std::vector<double> autocorrelation(const Eigen::VectorXd& e, int max_lag) {
  const Eigen::VectorXd x = centred(e);
  const double r0 = x.squaredNorm();
  std::vector<double> r(static_cast<std::size_t>(max_lag) + 1, 0.0);
  if (r0 <= 0) return r;
  for (int k = 0; k <= max_lag; ++k) r[static_cast<std::size_t>(k)] = lagged_sum(x, x, k) / r0;
  return r;
}

std::vector<double> cross_correlation(const Eigen::VectorXd& e, const Eigen::VectorXd& u, int max_lag) {
  const Eigen::VectorXd x = centred(e), v = centred(u);
  const double norm = std::sqrt(x.squaredNorm() * v.squaredNorm());
  std::vector<double> r(2 * static_cast<std::size_t>(max_lag) + 1, 0.0);
  if (norm <= 0) return r;
  for (int k = -max_lag; k <= max_lag; ++k) r[static_cast<std::size_t>(k + max_lag)] = lagged_sum(x, v, k) / norm;
  return r;
}

int allowed_outside(int judged) {
  // P(X > k) for X ~ Binomial(judged, 0.01), by the terms of P(X <= k) summed upwards.
  const double p = 0.01;
  double term = std::pow(1 - p, judged), cumulative = term;
  int k = 0;
  while (1 - cumulative >= 0.01 && k < judged) {
    term *= static_cast<double>(judged - k) / (k + 1) * p / (1 - p);
    cumulative += term;
    ++k;
  }
  return k;
}

bool CorrelationTest::passed() const { return outside <= allowed && beyond_simultaneous == 0; }

double two_sided_normal_quantile(double tail) {
  // Bisection on P(|Z| > z) = erfc(z / sqrt 2), decreasing in z.
  double lo = 0, hi = 40;
  for (int i = 0; i < 200; ++i) {
    const double mid = (lo + hi) / 2;
    (std::erfc(mid / std::sqrt(2.0)) > tail ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

CorrelationTest whiteness_test(const Eigen::VectorXd& e, int max_lag) {
  CorrelationTest t;
  t.values = autocorrelation(e, max_lag);
  for (int k = 0; k <= max_lag; ++k) t.lags.push_back(k);
  t.band = kResidualBandQuantile / std::sqrt(static_cast<double>(e.size()));
  judge(t, true);
  return t;
}

CorrelationTest independence_test(const Eigen::VectorXd& e, const Eigen::VectorXd& u, int max_lag) {
  CorrelationTest t;
  t.values = cross_correlation(e, u, max_lag);
  for (int k = -max_lag; k <= max_lag; ++k) t.lags.push_back(k);
  // P = sum over |k| <= L of rho_e(k) rho_u(k) (both symmetric in k); never below 0, which only the truncation of
  // the sum could give.
  const std::vector<double> re = autocorrelation(e, max_lag), ru = autocorrelation(u, max_lag);
  double P = re[0] * ru[0];
  for (int k = 1; k <= max_lag; ++k) P += 2 * re[static_cast<std::size_t>(k)] * ru[static_cast<std::size_t>(k)];
  t.band = kResidualBandQuantile * std::sqrt(std::max(P, 0.0) / static_cast<double>(e.size()));
  judge(t, false);
  return t;
}

std::vector<ChannelResidualTest> residual_tests(const Model& model, const std::vector<DataSet>& data,
                                                const Eigen::VectorXd& values, int max_lag) {
  std::vector<DataSet> records;
  for (const DataSet& d : data)
    if (!d.is_frf()) records.push_back(d);
  std::vector<ChannelResidualTest> out;
  if (records.empty()) return out;
  const Prediction at_estimate = predict(model, records, values);
  for (std::size_t d = 0; d < records.size(); ++d) {
    const TimeRecord& record = std::get<TimeRecord>(records[d].content);
    const int lags = std::max(0, std::min<int>(max_lag, static_cast<int>(record.samples() / 4)));
    for (std::size_t c = 0; c < at_estimate.channels[d].size(); ++c) {
      ChannelResidualTest test;
      test.data_set = record.file;
      test.output = at_estimate.channel_names[d][c];
      test.samples = static_cast<long>(record.samples());
      const Eigen::VectorXd e = record.at(test.output).values - at_estimate.channels[d][c].real();
      test.whiteness = whiteness_test(e, lags);
      for (const std::string& input : model.info().inputs)
        if (const Signal* u = record.find(input)) test.inputs.emplace_back(input, independence_test(e, u->values, lags));
      out.push_back(std::move(test));
    }
  }
  return out;
}

}  // namespace mbgen
