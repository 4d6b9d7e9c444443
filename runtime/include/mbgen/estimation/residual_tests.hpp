// Residual tests of a time-record fit, as MATLAB's `resid` draws them (docs/estimation.md, "Residual tests"):
//
//   whiteness     rho_e(k)  = sum_t e(t+k) e(t) / sum_t e(t)^2,                 k = 0..L
//   independence  rho_eu(k) = sum_t e(t+k) u(t) / sqrt(sum e^2 sum u^2),         k = -L..L
//
// e is a record's output residual y - yhat (measured minus the model simulated at the estimate), u one of its
// inputs, both with their means removed; a positive lag k pairs e with the input k samples earlier. The 99 % bands
// (Ljung, System Identification, 2nd ed., Sec. 16.6): +-2.58/sqrt(N) for rho_e(k), k >= 1, under the hypothesis that
// e is white; +-2.58 sqrt(P/N) with P = sum_{|k|<=L} rho_e(k) rho_u(k) for rho_eu, under the hypothesis that e is
// independent of u whatever the spectra of e and u (for white e, P = 1). A hypothesis is rejected when more lags lie
// outside its band than noise alone leaves there in 99 % of cases, or when one lag lies beyond the simultaneous 99 %
// band of all the lags judged.
#pragma once

#include "mbgen/data/data_set.hpp"
#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mbgen {

// The normal quantile of the two-sided 99 % band.
constexpr double kResidualBandQuantile = 2.58;

// One correlation sequence judged against its band.
struct CorrelationTest {
  std::vector<int> lags;
  std::vector<double> values;  // per lag
  double band = 0;             // half-width of the 99 % band
  int judged = 0;              // lags judged: 1..L for whiteness (rho_e(0) = 1 always), -L..L for independence
  int outside = 0;             // judged lags whose value lies outside the band
  int allowed = 0;             // allowed_outside(judged): more than this rejects the hypothesis
  // The simultaneous 99 % band of all judged lags (Bonferroni: each lag's two-sided level 0.01/judged): one lag
  // beyond it rejects the hypothesis too (a single strong peak, as a delayed copy of the input gives).
  double simultaneous_band = 0;
  int beyond_simultaneous = 0;  // judged lags beyond it
  bool passed() const;
  double fraction_outside() const { return judged > 0 ? static_cast<double>(outside) / judged : 0.0; }
};

// One output channel of one record.
struct ChannelResidualTest {
  std::string data_set;  // the record's file
  std::string output;    // the model output
  long samples = 0;      // N
  CorrelationTest whiteness;
  std::vector<std::pair<std::string, CorrelationTest>> inputs;  // per model input in the record, in model order
};

// Normalised autocorrelation rho_e(0..max_lag) of the mean-removed sequence (all zeros when it is constant).
std::vector<double> autocorrelation(const Eigen::VectorXd& e, int max_lag);
// Normalised cross-correlation rho_eu(-max_lag..max_lag) of the mean-removed sequences (of equal length).
std::vector<double> cross_correlation(const Eigen::VectorXd& e, const Eigen::VectorXd& u, int max_lag);

// The largest number of the `judged` lags that a sequence satisfying the hypothesis leaves outside a 99 % band
// with probability 99 % or more (binomial with p = 0.01, lags taken as independent): 2 of 25, 3 of 51.
int allowed_outside(int judged);
// The z with P(|Z| > z) = `tail` for a standard normal Z (2.5758 for 0.01).
double two_sided_normal_quantile(double tail);

CorrelationTest whiteness_test(const Eigen::VectorXd& e, int max_lag);
CorrelationTest independence_test(const Eigen::VectorXd& e, const Eigen::VectorXd& u, int max_lag);

// Both tests for every output of every time record in `data` (FRF data sets are skipped), the model simulated at
// `values` (all model parameters; each record's `# set` values applied on top). The lag is capped at N/4.
std::vector<ChannelResidualTest> residual_tests(const Model& model, const std::vector<DataSet>& data,
                                                const Eigen::VectorXd& values, int max_lag = 25);

}  // namespace mbgen
