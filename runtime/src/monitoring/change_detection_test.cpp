// The CUSUM's design (run length, threshold), its detection and change-point estimate, and the baseline scatter.
#include "mbgen/change_detection.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace mbgen;

TEST_CASE("Siegmund's run length matches simulated CUSUMs and the threshold inverts it", "[monitor]") {
  // The tabulated in-control ARL of the two-sided CUSUM for k = 0.5, h = 4 is 168 (Montgomery, Introduction to
  // Statistical Quality Control, Table 9.3): each of its two one-sided statistics has about twice that.
  CHECK(cusum_run_length(0.5, 4.0) / 2 == Approx(168).epsilon(0.03));
  CHECK(cusum_threshold(0.5, cusum_run_length(0.5, 4.0)) == Approx(4.0).epsilon(1e-9));
  // Simulated: 4000 runs on standard normal values, k = 0.5, h = 3.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const double k = 0.5, h = 3.0;
  double total = 0;
  const int runs = 4000;
  for (int r = 0; r < runs; ++r) {
    double s = 0;
    int n = 0;
    do {
      ++n;
      s = std::max(0.0, s + normal(rng) - k);
    } while (s <= h);
    total += n;
  }
  const double simulated = total / runs;  // its standard error is ~1.6 % (run lengths are near-geometric)
  CHECK(simulated == Approx(cusum_run_length(k, h)).epsilon(0.08));
}

TEST_CASE("a scheme of several streams gets a higher threshold", "[monitor]") {
  const double one = scheme_threshold(0.5, 1000, 1), seven = scheme_threshold(0.5, 1000, 7);
  CHECK(seven > one);
  CHECK(cusum_run_length(0.5, seven) == Approx(2 * 7 * 1000).epsilon(1e-9));
}

TEST_CASE("the two-sided CUSUM alarms on a step and estimates its onset", "[monitor]") {
  TwoSidedCusum c(0.5, 5.0);
  const double z[] = {0.3, -0.4, 0.8, -0.2, -2.5, -2.0, -2.7};
  int alarm = 0, at = -1;
  for (int i = 0; i < 7 && !alarm; ++i) {
    alarm = c.update(z[i], i);
    at = i;
  }
  CHECK(alarm == -1);
  CHECK(at == 6);
  CHECK(c.onset(-1) == 4);
  c.reset(at);
  CHECK(c.upper() == 0);
  CHECK(c.lower() == 0);
  CHECK(c.update(0.1, 7) == 0);
}

TEST_CASE("no alarm on in-control values at the scheme's threshold", "[monitor]") {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  const double h = scheme_threshold(0.5, 1000, 7);
  int alarms = 0;
  for (int p = 0; p < 7; ++p) {
    TwoSidedCusum c(0.5, h);
    for (int i = 0; i < 50; ++i) alarms += c.update(normal(rng), i) != 0;
  }
  CHECK(alarms == 0);
}

TEST_CASE("the baseline scatter is the larger of the sets' spread and the fits' std", "[monitor]") {
  const BaselineScatter spread = baseline_scatter({1.0, 2.0, 3.0}, {0.1, 0.1, 0.1});
  CHECK(spread.mean == Approx(2.0));
  CHECK(spread.sample_std == Approx(1.0));
  CHECK(spread.sigma == Approx(1.0));
  const BaselineScatter claimed = baseline_scatter({1.0, 1.0, 1.0}, {0.3, 0.4, 0.0});
  CHECK(claimed.sample_std == 0);
  CHECK(claimed.fit_std == Approx(std::sqrt((0.09 + 0.16) / 3)));
  CHECK(claimed.sigma == Approx(claimed.fit_std));
  // The reference mean's own uncertainty and a noisier new fit both widen the standardization.
  CHECK(standardized_shift(2.0, 0.0, 1.0, 1.0, 4) == Approx(1 / std::sqrt(1.25)));
  CHECK(standardized_shift(3.0, 2.0, 1.0, 1.0, 1) == Approx(2 / std::sqrt(5.0)));
}

TEST_CASE("the change point of a shift of unknown size", "[monitor]") {
  // Two sets slightly low, then a large drop: the drop's first set, where the CUSUM's own estimate says set 0.
  CHECK(change_point({{-1.06, -0.62, -470.0}}) == 2);
  TwoSidedCusum c(0.5, 5.0);
  int alarm = 0;
  const double z[] = {-1.06, -0.62, -470.0};
  for (int i = 0; i < 3; ++i) alarm = c.update(z[i], i);
  CHECK(c.onset(alarm) == 0);
  // A moderate shift over several sets in two streams, one without a value at one set.
  const double nan = std::nan("");
  CHECK(change_point({{0.1, -0.3, 2.1, 1.8, 2.4}, {0.2, nan, 1.9, 2.2, nan}}) == 2);
  CHECK(change_point({{0.0}}) == 0);
}
