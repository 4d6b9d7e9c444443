// The residual tests (mbgen/estimation/residual_tests.hpp) on sequences made by hand: exact correlations of short
// sequences, an AR(1) sequence flagged, a white sequence of a fixed seed passed, a delayed copy of the input found at
// its lag.
#include "mbgen/estimation/residual_tests.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

using namespace mbgen;

namespace {

// Standard normal numbers from a fixed seed by Box-Muller on std::mt19937_64's raw output (whose sequence the
// standard fixes, unlike std::normal_distribution's), so the sequences are the same on every platform.
Eigen::VectorXd gaussian(Eigen::Index n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto uniform = [&] { return (static_cast<double>(rng() >> 11) + 0.5) / 9007199254740992.0; };
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i)
    x[i] = std::sqrt(-2 * std::log(uniform())) * std::cos(2 * std::acos(-1.0) * uniform());
  return x;
}

Eigen::VectorXd ar1(const Eigen::VectorXd& w, double a) {
  Eigen::VectorXd e(w.size());
  e[0] = w[0];
  for (Eigen::Index t = 1; t < w.size(); ++t) e[t] = a * e[t - 1] + w[t];
  return e;
}

}  // namespace

TEST_CASE("correlations of short sequences computed by hand", "[residual_tests]") {
  // 1..5 less its mean 3: -2 -1 0 1 2, sum of squares 10; lag 1: 2 + 0 + 0 + 2 = 4; lag 2: 0 - 1 + 0 = -1.
  Eigen::VectorXd e(5);
  e << 1, 2, 3, 4, 5;
  const std::vector<double> r = autocorrelation(e, 2);
  REQUIRE(r.size() == 3);
  CHECK(r[0] == Approx(1));
  CHECK(r[1] == Approx(0.4));
  CHECK(r[2] == Approx(-0.1));
  // e(t) = u(t + 1): the input one sample later, the peak at lag -1 (a positive lag pairs e with earlier input).
  Eigen::VectorXd x(4), u(4);
  x << 1, -1, 0, 0;
  u << 0, 1, -1, 0;
  const std::vector<double> c = cross_correlation(x, u, 2);  // lags -2..2
  REQUIRE(c.size() == 5);
  CHECK(c[1] == Approx(1));     // lag -1: (1 * 1 + (-1) * (-1)) / sqrt(2 * 2)
  CHECK(c[2] == Approx(-0.5));  // lag 0: (-1 * 1) / 2
  CHECK(c[3] == Approx(0).margin(1e-15));
  // A constant sequence has no correlation to normalise: zeros, not NaN.
  CHECK(autocorrelation(Eigen::VectorXd::Constant(10, 3.0), 2) == std::vector<double>(3, 0.0));
}

TEST_CASE("the number of lags allowed outside a 99 % band", "[residual_tests]") {
  // Binomial(n, 0.01): P(X > 2) = 0.0020 for n = 25 (P(X > 1) = 0.026); P(X > 3) = 0.0019 for n = 51 (P(X > 2) =
  // 0.0145).
  CHECK(allowed_outside(25) == 2);
  CHECK(allowed_outside(51) == 3);
  CHECK(allowed_outside(0) == 0);
  CHECK(allowed_outside(5) == 1);  // P(X > 0) = 0.049, P(X > 1) = 0.00098
  CHECK(two_sided_normal_quantile(0.01) == Approx(2.5758).epsilon(1e-4));
  CHECK(two_sided_normal_quantile(0.05) == Approx(1.9600).epsilon(1e-4));
}

TEST_CASE("an AR(1) residual is not white", "[residual_tests]") {
  const Eigen::VectorXd e = ar1(gaussian(2000, 7), 0.8);
  const CorrelationTest t = whiteness_test(e, 25);
  CHECK(t.band == Approx(2.58 / std::sqrt(2000.0)));
  CHECK(t.judged == 25);
  CHECK(t.values[1] == Approx(0.8).margin(0.05));
  CHECK(t.outside > 10);
  CHECK_FALSE(t.passed());
}

TEST_CASE("a white residual of a fixed seed passes both tests", "[residual_tests]") {
  const Eigen::VectorXd e = gaussian(2000, 11), u = gaussian(2000, 12);
  const CorrelationTest w = whiteness_test(e, 25);
  CHECK(w.outside <= w.allowed);
  CHECK(w.passed());
  const CorrelationTest x = independence_test(e, u, 25);
  CHECK(x.judged == 51);
  CHECK(x.passed());
  CHECK(x.band == Approx(2.58 / std::sqrt(2000.0)).epsilon(0.1));  // P near 1 for white e
}

TEST_CASE("a residual that is a delayed copy of the input shows the correlation at that lag", "[residual_tests]") {
  const Eigen::Index n = 2000;
  const Eigen::VectorXd u = gaussian(n, 21), w = gaussian(n, 22);
  Eigen::VectorXd e = 0.5 * w;
  e.tail(n - 3) += u.head(n - 3);  // e(t) = u(t - 3) + noise
  const CorrelationTest x = independence_test(e, u, 25);
  CHECK_FALSE(x.passed());
  CHECK(x.beyond_simultaneous >= 1);
  CHECK(x.simultaneous_band / x.band == Approx(two_sided_normal_quantile(0.01 / 51) / 2.58));
  const auto peak = std::max_element(x.values.begin(), x.values.end(),
                                     [](double a, double b) { return std::abs(a) < std::abs(b); }) - x.values.begin();
  CHECK(x.lags[static_cast<std::size_t>(peak)] == 3);
  CHECK(x.values[static_cast<std::size_t>(peak)] == Approx(1 / std::sqrt(1.25)).margin(0.03));
  CHECK(x.outside <= 3);  // only at (and by chance near) the delay
  // The residual is white all the same: only the cross-correlation sees the input in it.
  CHECK(whiteness_test(e, 25).passed());
}

TEST_CASE("the cross-correlation band widens with both sequences' own correlation (Ljung)", "[residual_tests]") {
  // Two independent AR(1) sequences, a = 0.8: P = sum_k a^2|k| = (1 + a^2) / (1 - a^2) = 4.56, a band sqrt(4.56) =
  // 2.13 times the white one; within it they are independent, while the white band would call them correlated.
  const Eigen::Index n = 4000;
  const Eigen::VectorXd e = ar1(gaussian(n, 31), 0.8), u = ar1(gaussian(n, 32), 0.8);
  const CorrelationTest x = independence_test(e, u, 25);
  const double white_band = 2.58 / std::sqrt(static_cast<double>(n));
  CHECK(x.band / white_band == Approx(std::sqrt(1.64 / 0.36)).epsilon(0.15));
  CHECK(x.passed());
  const auto outside_white = std::count_if(x.values.begin(), x.values.end(), [&](double v) { return std::abs(v) > white_band; });
  CHECK(outside_white > x.allowed);
}
