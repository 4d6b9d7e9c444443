#include "numerics/polynomial_roots.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using mbgen::numerics::polynomial_roots;
using Complex = std::complex<double>;

namespace {

// Ascending coefficients of prod_k (s - r_k), in long double so that the test's data do not share the code's rounding.
Eigen::VectorXd from_roots(const std::vector<Complex>& roots) {
  std::vector<std::complex<long double>> c{1.0L};
  for (const Complex& r : roots) {
    std::vector<std::complex<long double>> next(c.size() + 1, 0.0L);
    for (std::size_t j = 0; j < c.size(); ++j) {
      next[j + 1] += c[j];
      next[j] -= std::complex<long double>(r.real(), r.imag()) * c[j];
    }
    c = next;
  }
  Eigen::VectorXd out(static_cast<Eigen::Index>(c.size()));
  for (std::size_t j = 0; j < c.size(); ++j) out[static_cast<Eigen::Index>(j)] = static_cast<double>(c[j].real());
  return out;
}

// Each expected root has a computed one within rel of its magnitude.
void check_roots(const std::vector<Complex>& got, const std::vector<Complex>& expected, double rel) {
  REQUIRE(got.size() == expected.size());
  for (const Complex& e : expected) {
    double nearest = INFINITY;
    for (const Complex& g : got) nearest = std::min(nearest, std::abs(g - e));
    CHECK(nearest <= rel * std::max(std::abs(e), 1e-300));
  }
}

}  // namespace

TEST_CASE("polynomial roots: constants, zeros at the origin, dropped leading zeros", "[numerics]") {
  CHECK(polynomial_roots(Eigen::VectorXd()).empty());
  CHECK(polynomial_roots(Eigen::Vector2d(3, 0)).empty());
  const auto at_origin = polynomial_roots(Eigen::Vector4d(0, 0, -2, 1));  // s^2 (s - 2)
  REQUIRE(at_origin.size() == 3);
  CHECK(at_origin[0] == Complex(0, 0));
  CHECK(at_origin[1] == Complex(0, 0));
  CHECK(std::abs(at_origin[2] - 2.0) < 1e-15);
  check_roots(polynomial_roots(Eigen::Vector4d(6, -5, 1, 0)), {2.0, 3.0}, 1e-14);  // (s-2)(s-3), then a zero
}

TEST_CASE("polynomial roots of a two-mode mechanical denominator spanning 1e0 .. 1e22", "[numerics]") {
  // Poles of a stiff two-degree-of-freedom structure: 80 Hz and 3 kHz, light damping. The coefficients of the
  // monic quartic span about 22 orders of magnitude; the scaled companion keeps the relative accuracy.
  const double w1 = 2 * M_PI * 80, w2 = 2 * M_PI * 3000, z1 = 0.01, z2 = 0.002;
  const Complex p1(-z1 * w1, w1 * std::sqrt(1 - z1 * z1)), p2(-z2 * w2, w2 * std::sqrt(1 - z2 * z2));
  const std::vector<Complex> poles{p1, std::conj(p1), p2, std::conj(p2)};
  Eigen::VectorXd c = from_roots(poles);
  c *= 1e-6;  // a mass in the leading coefficient: the scaling must not assume a monic polynomial
  const auto roots = polynomial_roots(c);
  check_roots(roots, poles, 1e-12);
  // Conjugate pairs come out as exact conjugates (real Schur form).
  int upper = 0, lower = 0;
  for (const Complex& r : roots) (r.imag() > 0 ? upper : lower) += 1;
  CHECK(upper == 2);
  CHECK(lower == 2);
}
