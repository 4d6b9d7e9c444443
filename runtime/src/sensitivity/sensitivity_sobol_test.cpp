// Sobol indices of the Ishigami function, whose indices are known in closed form (Ishigami & Homma 1990;
// Saltelli et al. 2008, Sec. 4.6): f = sin x1 + a sin^2 x2 + b x3^4 sin x1 on [-pi, pi]^3.
#include "mbgen/sensitivity/sensitivity.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

namespace mbgen {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double a = 7, b = 0.1;

Eigen::VectorXd ishigami(const Eigen::VectorXd& u) {
  const Eigen::VectorXd x = (2 * u.array() - 1) * kPi;
  Eigen::VectorXd y(1);
  y[0] = std::sin(x[0]) + a * std::pow(std::sin(x[1]), 2) + b * std::pow(x[2], 4) * std::sin(x[0]);
  return y;
}

// V = a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2, V1 = (1 + b pi^4/5)^2 / 2, V2 = a^2/8, V13 = 8 b^2 pi^8 / 225, V3 = 0.
struct Exact {
  double v1 = 0.5 * std::pow(1 + b * std::pow(kPi, 4) / 5, 2), v2 = a * a / 8, v13 = 8 * b * b * std::pow(kPi, 8) / 225;
  double v = v1 + v2 + v13;
  double first(int i) const { return i == 0 ? v1 / v : i == 1 ? v2 / v : 0.0; }
  double total(int i) const { return i == 0 ? (v1 + v13) / v : i == 1 ? v2 / v : v13 / v; }
};

}  // namespace

TEST_CASE("Sobol indices of the Ishigami function", "[sensitivity][sobol]") {
  const Exact exact;
  REQUIRE(exact.first(0) == Approx(0.3139).epsilon(1e-3));  // the published values
  REQUIRE(exact.total(2) == Approx(0.2437).epsilon(1e-3));
  SobolOptions options;
  options.samples = 1 << 14;
  options.seed = 7;
  const SobolIndices s = sobol_indices(ishigami, 3, 1, options);
  CHECK(s.evaluations == (1 << 14) * 5);
  CHECK(s.used[0] == 1 << 14);
  CHECK(s.variance[0] == Approx(exact.v).epsilon(0.03));
  for (int i = 0; i < 3; ++i) {
    INFO("x" << i + 1 << ": S " << s.first(0, i) << " +- " << s.first_std(0, i) << " (exact " << exact.first(i)
             << "), ST " << s.total(0, i) << " +- " << s.total_std(0, i) << " (exact " << exact.total(i) << ")");
    // Within 4 standard errors, and the standard errors small: the estimates are tight.
    CHECK(std::abs(s.first(0, i) - exact.first(i)) < 4 * s.first_std(0, i));
    CHECK(std::abs(s.total(0, i) - exact.total(i)) < 4 * s.total_std(0, i));
    CHECK(s.first_std(0, i) < 0.015);
    CHECK(s.total_std(0, i) < 0.015);
  }
}

TEST_CASE("Sobol indices do not depend on the number of threads, and skip undefined samples", "[sensitivity][sobol]") {
  SobolOptions one, two;
  one.samples = two.samples = 512;
  one.threads = 1;
  two.threads = 2;
  const SobolIndices s1 = sobol_indices(ishigami, 3, 1, one), s2 = sobol_indices(ishigami, 3, 1, two);
  CHECK(s1.first == s2.first);
  CHECK(s1.total == s2.total);
  CHECK(s1.variance == s2.variance);
  // A second output undefined for x1 > 0.5 (in unit coordinates): only samples with every evaluation defined count.
  const auto partial = [](const Eigen::VectorXd& u) {
    Eigen::VectorXd y(2);
    y[0] = ishigami(u)[0];
    y[1] = u[0] > 0.5 ? std::numeric_limits<double>::quiet_NaN() : u[1];
    return y;
  };
  const SobolIndices s = sobol_indices(partial, 3, 2, one);
  CHECK(s.used[0] == 512);
  CHECK(s.used[1] > 100);
  CHECK(s.used[1] < 200);  // A and A_B^(1) both need x1 <= 0.5: about a quarter
  CHECK(s.first(0, 0) == s1.first(0, 0));
  CHECK(std::abs(s.total(1, 1) - 1) < 4 * s.total_std(1, 1));  // y = x2 alone
  CHECK(std::abs(s.total(1, 0)) < 4 * s.total_std(1, 0) + 1e-12);
}

}  // namespace mbgen
