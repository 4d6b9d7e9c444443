#include "mbgen/dynamics/model_modes.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"
#include "mbgen_test/mdof2.hpp"

#include <catch2/catch.hpp>

#include <Eigen/LU>

#include <cmath>

using mbgen::Mode;

namespace {

const double pi = std::acos(-1.0);

// Table 5.1, assembled by hand (independent of the model classes).
mbgen::ModelMatrices mdof2_matrices() { return mbgen::test::mdof2_matrices(); }

}  // namespace

TEST_CASE("mdof2 modes match the reference frequencies and damping ratios") {
  const auto m = mdof2_matrices();
  const auto modes = mbgen::modal_analysis(m.M, m.C, m.K);
  REQUIRE(modes.size() == 2);
  // docs/reference-models.md: 89.72 Hz (zeta 0.000514) and 166.29 Hz (zeta 0.00455), sorted by frequency.
  CHECK(modes[0].f_hz == Approx(89.72).margin(0.005));
  CHECK(modes[0].zeta == Approx(0.000514).margin(0.0000005));
  CHECK(modes[1].f_hz == Approx(166.29).margin(0.005));
  CHECK(modes[1].zeta == Approx(0.00455).margin(0.000005));
  for (const Mode& mode : modes) {
    CHECK(mode.eigenvalue.imag() > 0);
    CHECK(std::abs(mode.eigenvalue) / (2 * pi) == Approx(mode.f_hz));
    CHECK(-mode.eigenvalue.real() / std::abs(mode.eigenvalue) == Approx(mode.zeta));
    // The shape solves the quadratic eigenproblem (lambda^2 M + lambda C + K) v = 0.
    const std::complex<double> s = mode.eigenvalue;
    const Eigen::MatrixXcd P = s * s * m.M.cast<std::complex<double>>() + s * m.C.cast<std::complex<double>>() +
                               m.K.cast<std::complex<double>>();
    CHECK((P * mode.shape).norm() <= 1e-9 * P.norm() * mode.shape.norm());
    CHECK(mode.shape.cwiseAbs().maxCoeff() == Approx(1.0).epsilon(1e-15));
  }
  // The lower mode moves both masses in phase, the upper one against each other (k12 couples them).
  CHECK(std::real(modes[0].shape[0] * std::conj(modes[0].shape[1])) > 0);
  CHECK(std::real(modes[1].shape[0] * std::conj(modes[1].shape[1])) < 0);
}

TEST_CASE("undamped natural frequencies solve the 2x2 characteristic polynomial") {
  const auto m = mdof2_matrices();
  const auto f = mbgen::undamped_natural_frequencies_hz(m.M, m.K);
  REQUIRE(f.size() == 2);
  // det(K - w^2 M) = m1 m2 w^4 - (m1 K22 + m2 K11) w^2 + det K = 0, solved by the quadratic formula.
  const double a = m.M(0, 0) * m.M(1, 1), b = -(m.M(0, 0) * m.K(1, 1) + m.M(1, 1) * m.K(0, 0)),
               c = m.K.determinant();
  const double disc = std::sqrt(b * b - 4 * a * c);
  const double w2_low = (-b - disc) / (2 * a), w2_high = (-b + disc) / (2 * a);
  CHECK(f[0] == Approx(std::sqrt(w2_low) / (2 * pi)).epsilon(1e-12));
  CHECK(f[1] == Approx(std::sqrt(w2_high) / (2 * pi)).epsilon(1e-12));
}

TEST_CASE("a rigid-body mode has zero undamped frequency") {
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(2, 2), K(2, 2);
  K << 5, -5, -5, 5;  // free-free: eigenvalues 0 and 10
  const auto f = mbgen::undamped_natural_frequencies_hz(M, K);
  CHECK(f[0] == Approx(0).margin(1e-7));
  CHECK(f[1] == Approx(std::sqrt(10.0) / (2 * pi)).epsilon(1e-12));
}

TEST_CASE("overdamped single degree of freedom gives two real modes") {
  // s^2 + 5 s + 4 = (s + 1)(s + 4).
  Eigen::MatrixXd M(1, 1), C(1, 1), K(1, 1);
  M << 1;
  C << 5;
  K << 4;
  const auto modes = mbgen::modal_analysis(M, C, K);
  REQUIRE(modes.size() == 2);
  CHECK(modes[0].eigenvalue.real() == Approx(-1.0).epsilon(1e-12));
  CHECK(modes[0].eigenvalue.imag() == 0.0);
  CHECK(modes[0].f_hz == Approx(1 / (2 * pi)).epsilon(1e-12));
  CHECK(modes[0].zeta == 1.0);
  CHECK(modes[1].eigenvalue.real() == Approx(-4.0).epsilon(1e-12));
  CHECK(modes[1].zeta == 1.0);
}

TEST_CASE("underdamped single degree of freedom") {
  // s^2 + 2 zeta w s + w^2 with w = 2 pi 10, zeta = 0.05.
  const double w = 2 * pi * 10, zeta = 0.05;
  Eigen::MatrixXd M(1, 1), C(1, 1), K(1, 1);
  M << 2;
  C << 2 * 2 * zeta * w;
  K << 2 * w * w;
  const auto modes = mbgen::modal_analysis(M, C, K);
  REQUIRE(modes.size() == 1);
  CHECK(modes[0].f_hz == Approx(10.0).epsilon(1e-12));
  CHECK(modes[0].zeta == Approx(zeta).epsilon(1e-12));
  CHECK(modes[0].eigenvalue.imag() == Approx(w * std::sqrt(1 - zeta * zeta)).epsilon(1e-12));
}

TEST_CASE("MAC of a mode set with itself") {
  // Proportional damping with M = I: real, orthogonal shapes, so MAC(modes, modes) is the identity.
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(3, 3), K(3, 3);
  K << 2, -1, 0, -1, 2, -1, 0, -1, 2;
  K *= 1e4;
  const Eigen::MatrixXd C = 1e-3 * K;
  const auto modes = mbgen::modal_analysis(M, C, K);
  REQUIRE(modes.size() == 3);
  const Eigen::MatrixXd mac = mbgen::modal_assurance_criterion(modes, modes);
  CHECK((mac - Eigen::MatrixXd::Identity(3, 3)).cwiseAbs().maxCoeff() < 1e-12);

  // Non-proportional damping (mdof2): the diagonal is still exactly one, and MAC ignores complex scaling.
  const auto m = mdof2_matrices();
  auto complex_modes = mbgen::modal_analysis(m.M, m.C, m.K);
  const Eigen::MatrixXd mac2 = mbgen::modal_assurance_criterion(complex_modes, complex_modes);
  CHECK(mac2(0, 0) == Approx(1.0).epsilon(1e-14));
  CHECK(mac2(1, 1) == Approx(1.0).epsilon(1e-14));
  CHECK(mac2(0, 1) == Approx(mac2(1, 0)).epsilon(1e-12));
  auto scaled = complex_modes;
  scaled[0].shape *= std::complex<double>(-3.0, 2.0);
  CHECK((mbgen::modal_assurance_criterion(scaled, complex_modes) - mac2).cwiseAbs().maxCoeff() < 1e-14);
  // Hand-computed MAC of two simple vectors: |(1, i)^H (1, 1)|^2 / (2 * 2) = |1 + (-i)|^2 / 4 = 0.5.
  Eigen::MatrixXcd a(2, 1), b(2, 1);
  a << 1.0, std::complex<double>(0, 1);
  b << 1.0, 1.0;
  CHECK(mbgen::modal_assurance_criterion(a, b)(0, 0) == Approx(0.5).epsilon(1e-15));
}

TEST_CASE("modal analysis rejects a singular mass matrix") {
  Eigen::MatrixXd M(2, 2), K(2, 2), C = Eigen::MatrixXd::Zero(2, 2);
  M << 1, 0, 0, 0;
  K << 2, -1, -1, 2;
  CHECK_THROWS_AS(mbgen::modal_analysis(M, C, K), mbgen::DynamicsError);
  CHECK_THROWS_WITH(mbgen::modal_analysis(M, C, K), Catch::Contains("mass matrix M is singular"));
  CHECK_THROWS_AS(mbgen::undamped_natural_frequencies_hz(M, K), mbgen::DynamicsError);
  CHECK_THROWS_WITH(mbgen::modal_analysis(Eigen::MatrixXd::Identity(2, 2), C, Eigen::MatrixXd::Identity(3, 3)),
                    Catch::Contains("matrix K is 3x3, expected 2x2"));
}

TEST_CASE("the hand-written mdof2 Model gives the same modes") {
  mbgen::test::Mdof2Model model;
  mbgen::ModelMatrices m;
  model.evaluate(model.info().default_values(), m);
  const auto modes = mbgen::modal_analysis(m.M, m.C, m.K);
  REQUIRE(modes.size() == 2);
  CHECK(modes[0].f_hz == Approx(89.72).margin(0.005));
  CHECK(modes[1].f_hz == Approx(166.29).margin(0.005));
}

TEST_CASE("stiff spindle-sized system with stiffness-proportional damping") {
  // 11 coordinates, masses 0.05..25 and springs 3e7..1.3e8 (spindle magnitudes), C = beta K. For proportional
  // damping every mode has |lambda| = w_n exactly and zeta = beta w_n / 2: independent of the state-space route.
  const int n = 11;
  const double beta = 1e-5;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), K = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) M(i, i) = i % 2 == 0 ? 5.0 + 2.0 * i : 0.05 + 0.03 * i;
  auto spring = [&](int a, int b, double k) {
    K(a, a) += k;
    if (b >= 0) {
      K(b, b) += k;
      K(a, b) -= k;
      K(b, a) -= k;
    }
  };
  for (int i = 0; i < n; ++i) spring(i, i - 1, 3e7 + 1e7 * i);
  spring(0, 7, 6e7);
  spring(3, 10, 1.3e8);
  const Eigen::MatrixXd C = beta * K;
  const auto modes = mbgen::modal_analysis(M, C, K);
  const Eigen::VectorXd f = mbgen::undamped_natural_frequencies_hz(M, K);
  REQUIRE(modes.size() == static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    INFO("mode " << i);
    CHECK(modes[static_cast<std::size_t>(i)].f_hz == Approx(f[i]).epsilon(1e-10));
    CHECK(modes[static_cast<std::size_t>(i)].zeta == Approx(beta * 2 * pi * f[i] / 2).epsilon(1e-7));
  }
}
