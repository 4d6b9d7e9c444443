#include "mbgen/dynamics/state_space.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"
#include "mbgen_test/mdof2.hpp"
#include "mbgen_test/random_affine_model.hpp"
#include "mbgen_test/finite_difference.hpp"
#include "test_rk4.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <cmath>
#include <random>

namespace {

using cd = std::complex<double>;
const double pi = std::acos(-1.0);

mbgen::ModelMatrices mdof2_matrices(bool extra_outputs) { return mbgen::test::mdof2_matrices({}, extra_outputs); }

Eigen::MatrixXd simulate_positions(const mbgen::DiscreteStateSpace& sys, const Eigen::MatrixXd& u, Eigen::Index n) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(sys.Phi.rows());
  Eigen::MatrixXd q(u.rows(), n);
  for (Eigen::Index k = 0; k < u.rows(); ++k) {
    q.row(k) = x.head(n).transpose();
    const Eigen::VectorXd next_u = k + 1 < u.rows() ? Eigen::VectorXd(u.row(k + 1).transpose())
                                                    : Eigen::VectorXd::Zero(u.cols());
    x = sys.Phi * x + sys.Gamma0 * u.row(k).transpose() + sys.Gamma1 * next_u;
  }
  return q;
}

}  // namespace

TEST_CASE("continuous state space reproduces the mdof2 transfer functions, including acceleration outputs") {
  const auto m = mdof2_matrices(/*extra_outputs=*/true);
  const auto ss = mbgen::state_space(m);
  REQUIRE(ss.A.rows() == 4);
  REQUIRE(ss.C.rows() == 4);
  const double m1 = 1.39, m2 = 1.09, k11 = 1.38e6, k22 = 0.24e6, k12 = 0.12e6, c11 = 13.42, c22 = 0.47;
  for (double f : {3.0, 89.7, 120.0, 166.3, 500.0}) {
    const cd s(0, 2 * pi * f);
    const cd den = s * s * s * s + (c11 * m2 + c22 * m1) / (m1 * m2) * s * s * s +
                   (c11 * c22 + k11 * m2 + k12 * m1 + k12 * m2 + k22 * m1) / (m1 * m2) * s * s +
                   (c11 * k12 + c11 * k22 + c22 * k11 + c22 * k12) / (m1 * m2) * s +
                   (k11 * k12 + k11 * k22 + k12 * k22) / (m1 * m2);
    const cd g11 = (s * s / m1 + c22 / (m1 * m2) * s + (k12 + k22) / (m1 * m2)) / den;
    const cd g21 = (k12 / (m1 * m2)) / den;
    const Eigen::MatrixXcd I = Eigen::MatrixXcd::Identity(4, 4);
    const Eigen::MatrixXcd G = ss.C.cast<cd>() * (s * I - ss.A.cast<cd>()).partialPivLu().solve(ss.B.cast<cd>()) +
                               ss.D.cast<cd>();
    INFO("f = " << f);
    CHECK(std::abs(G(0, 0) - g11) <= 1e-9 * std::abs(g11));
    CHECK(std::abs(G(1, 0) - g21) <= 1e-9 * std::abs(g21));
    CHECK(std::abs(G(2, 0) - s * g11) <= 1e-9 * std::abs(s * g11));
    CHECK(std::abs(G(3, 0) - s * s * g21) <= 1e-9 * std::abs(s * s * g21));
  }
}

TEST_CASE("an acceleration output at the force gives D = 1/m1") {
  auto m = mdof2_matrices(false);
  m.Cd.setZero();
  m.Ca(0, 0) = 1;  // y0 = q1''
  const auto ss = mbgen::state_space(m);
  CHECK(ss.D(0, 0) == Approx(1 / 1.39).epsilon(1e-14));
  CHECK(ss.D(1, 0) == 0.0);
  // q1'' = (F - (k11 + k12) q1 + k12 q2 - c11 q1') / m1
  CHECK(ss.C(0, 0) == Approx(-(1.38e6 + 0.12e6) / 1.39).epsilon(1e-14));
  CHECK(ss.C(0, 1) == Approx(0.12e6 / 1.39).epsilon(1e-14));
  CHECK(ss.C(0, 2) == Approx(-13.42 / 1.39).epsilon(1e-14));
}

namespace {
template <class Eval>
void check_derivatives_by_central_differences(const mbgen::Model& model, Eval eval_flat, double rel) {
  const Eigen::VectorXd p = model.info().default_values();
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    const Eigen::VectorXd fd = mbgen::test::central_difference(
        [&](const Eigen::VectorXd& q) { return eval_flat(q, -1); }, p, i, mbgen::test::central_step(p[i]));
    const Eigen::VectorXd analytic = eval_flat(p, i);
    INFO("parameter " << model.info().parameters[static_cast<std::size_t>(i)].name);
    CHECK((analytic - fd).norm() <= rel * std::max(analytic.norm(), 1e-12 * eval_flat(p, -1).norm() / std::max(std::abs(p[i]), 1.0)));
  }
}

Eigen::VectorXd flatten(std::initializer_list<const Eigen::MatrixXd*> parts) {
  Eigen::Index size = 0;
  for (auto* part : parts) size += part->size();
  Eigen::VectorXd v(size);
  Eigen::Index offset = 0;
  for (auto* part : parts) {
    v.segment(offset, part->size()) = Eigen::Map<const Eigen::VectorXd>(part->data(), part->size());
    offset += part->size();
  }
  return v;
}
}  // namespace

TEST_CASE("state-space derivatives match central finite differences") {
  for (int which = 0; which < 2; ++which) {
    const mbgen::test::Mdof2Model mdof2(true);
    const mbgen::test::RandomAffineModel random(4, 2, 3, 12, 7);
    const mbgen::Model& model = which == 0 ? static_cast<const mbgen::Model&>(mdof2) : random;
    auto eval = [&](const Eigen::VectorXd& p, int derivative) {
      mbgen::ModelMatrices m;
      model.evaluate(p, m);
      if (derivative < 0) {
        const auto ss = mbgen::state_space(m);
        return flatten({&ss.A, &ss.B, &ss.C, &ss.D});
      }
      mbgen::ModelDerivatives d;
      model.derivatives(p, d);
      const auto ds = mbgen::state_space_derivatives(m, d, static_cast<int>(p.size()));
      const auto& s = ds[static_cast<std::size_t>(derivative)];
      return flatten({&s.A, &s.B, &s.C, &s.D});
    };
    check_derivatives_by_central_differences(model, eval, 1e-6);
  }
}

TEST_CASE("ZOH discretisation gives the exact step response of one degree of freedom") {
  const double mass = 2, k = 8e4, c = 20, force = 3, dt = 1e-3;
  const double w = std::sqrt(k / mass), zeta = c / (2 * mass * w), wd = w * std::sqrt(1 - zeta * zeta);
  mbgen::ModelMatrices m;
  m.M = Eigen::MatrixXd::Constant(1, 1, mass);
  m.C = Eigen::MatrixXd::Constant(1, 1, c);
  m.K = Eigen::MatrixXd::Constant(1, 1, k);
  m.B = Eigen::MatrixXd::Ones(1, 1);
  m.Cd = Eigen::MatrixXd::Ones(1, 1);
  m.Cv = Eigen::MatrixXd::Zero(1, 1);
  m.Ca = Eigen::MatrixXd::Zero(1, 1);
  for (auto hold : {mbgen::InputHold::ZeroOrder, mbgen::InputHold::FirstOrder}) {
    // A constant input is both held and linearly interpolated: both holds are exact for it.
    const auto sys = mbgen::discretize(mbgen::state_space(m), dt, hold);
    const Eigen::MatrixXd q = simulate_positions(sys, Eigen::MatrixXd::Constant(400, 1, force), 1);
    for (int i = 0; i < 400; ++i) {
      const double t = i * dt;
      const double exact =
          force / k * (1 - std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t)));
      CHECK(q(i, 0) == Approx(exact).margin(1e-12 * force / k));
    }
  }
}

TEST_CASE("Phi equals the exponential computed by eigendecomposition") {
  const auto m = mdof2_matrices(false);
  const auto ss = mbgen::state_space(m);
  const double dt = 2.5e-4;
  const auto sys = mbgen::discretize(ss, dt, mbgen::InputHold::ZeroOrder);
  Eigen::EigenSolver<Eigen::MatrixXd> eig(ss.A);
  const Eigen::MatrixXcd V = eig.eigenvectors();
  const Eigen::VectorXcd expLambda = (eig.eigenvalues() * dt).array().exp();
  const Eigen::MatrixXd Phi = (V * expLambda.asDiagonal() * V.inverse()).real();
  CHECK((sys.Phi - Phi).norm() <= 1e-11 * Phi.norm());
  // Gamma0 = A^-1 (Phi - I) B for invertible A.
  const Eigen::MatrixXd Gamma = ss.A.partialPivLu().solve((Phi - Eigen::MatrixXd::Identity(4, 4)) * ss.B);
  CHECK((sys.Gamma0 - Gamma).norm() <= 1e-9 * Gamma.norm());
  CHECK(sys.Gamma1.norm() == 0.0);
}

TEST_CASE("ZOH and FOH discretisations match a fine RK4 integration") {
  const auto m = mdof2_matrices(false);
  const mbgen::test::SecondOrderRk4 rk4{m.M, m.C, m.K, m.B};
  const double dt = 1e-3;  // 166 Hz mode: w dt ~ 1
  const int samples = 60;
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0, 100);
  Eigen::MatrixXd u(samples, 1);
  for (int k = 0; k < samples; ++k) u(k, 0) = normal(rng);
  const auto ss = mbgen::state_space(m);

  SECTION("zero-order hold: piecewise-constant input") {
    auto held = [&](int k, double) { return Eigen::VectorXd::Constant(1, u(k, 0)); };
    const Eigen::MatrixXd reference = rk4.run(held, samples, dt, 2000).leftCols(2);
    const Eigen::MatrixXd q = simulate_positions(mbgen::discretize(ss, dt, mbgen::InputHold::ZeroOrder), u, 2);
    CHECK((q - reference).cwiseAbs().maxCoeff() <= 1e-9 * reference.cwiseAbs().maxCoeff());
  }
  SECTION("first-order hold: piecewise-linear input") {
    auto linear = [&](int k, double a) {
      const double next = k + 1 < samples ? u(k + 1, 0) : 0.0;
      return Eigen::VectorXd::Constant(1, (1 - a) * u(k, 0) + a * next);
    };
    const Eigen::MatrixXd reference = rk4.run(linear, samples, dt, 2000).leftCols(2);
    const Eigen::MatrixXd q = simulate_positions(mbgen::discretize(ss, dt, mbgen::InputHold::FirstOrder), u, 2);
    CHECK((q - reference).cwiseAbs().maxCoeff() <= 1e-9 * reference.cwiseAbs().maxCoeff());
    // ... and the zero-order hold of the same samples is a different (wrong) answer for this input.
    const Eigen::MatrixXd zoh = simulate_positions(mbgen::discretize(ss, dt, mbgen::InputHold::ZeroOrder), u, 2);
    CHECK((zoh - reference).cwiseAbs().maxCoeff() > 1e-3 * reference.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("discretisation derivatives match central finite differences") {
  const mbgen::test::Mdof2Model mdof2(true);
  const mbgen::test::RandomAffineModel random(4, 2, 3, 12, 11);
  for (auto hold : {mbgen::InputHold::ZeroOrder, mbgen::InputHold::FirstOrder}) {
    for (int which = 0; which < 2; ++which) {
      const mbgen::Model& model = which == 0 ? static_cast<const mbgen::Model&>(mdof2) : random;
      const double dt = which == 0 ? 5e-4 : 2e-3;
      auto eval = [&](const Eigen::VectorXd& p, int derivative) {
        mbgen::ModelMatrices m;
        model.evaluate(p, m);
        const auto ss = mbgen::state_space(m);
        if (derivative < 0) {
          const auto sys = mbgen::discretize(ss, dt, hold);
          return flatten({&sys.Phi, &sys.Gamma0, &sys.Gamma1, &sys.C, &sys.D});
        }
        mbgen::ModelDerivatives d;
        model.derivatives(p, d);
        const auto ds = mbgen::discretize_derivatives(ss, mbgen::state_space_derivatives(m, d, static_cast<int>(p.size())), dt, hold);
        const auto& s = ds[static_cast<std::size_t>(derivative)];
        return flatten({&s.Phi, &s.Gamma0, &s.Gamma1, &s.C, &s.D});
      };
      INFO("model " << which << ", hold " << static_cast<int>(hold));
      check_derivatives_by_central_differences(model, eval, 1e-6);
    }
  }
}

TEST_CASE("state space errors") {
  auto m = mdof2_matrices(false);
  m.M(1, 1) = 0;  // massless coordinate
  CHECK_THROWS_WITH(mbgen::state_space(m), Catch::Contains("state_space: mass matrix M is singular"));
  const auto ss = mbgen::state_space(mdof2_matrices(false));
  CHECK_THROWS_WITH(mbgen::discretize(ss, 0.0, mbgen::InputHold::ZeroOrder), Catch::Contains("must be positive"));
  CHECK_THROWS_WITH(mbgen::discretize(ss, std::nan(""), mbgen::InputHold::ZeroOrder), Catch::Contains("must be positive"));
  auto bad = ss;
  bad.B.resize(3, 1);
  CHECK_THROWS_WITH(mbgen::discretize(bad, 1e-3, mbgen::InputHold::ZeroOrder), Catch::Contains("matrix B is 3x1"));
}
