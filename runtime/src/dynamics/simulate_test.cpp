#include "mbgen/dynamics/simulate.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"
#include "mbgen_test/mdof2.hpp"
#include "mbgen_test/random_affine_model.hpp"
#include "test_rk4.hpp"

#include <catch2/catch.hpp>

#include <random>

namespace {

Eigen::MatrixXd random_force(int samples, int inputs, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0, 50);
  Eigen::MatrixXd u(samples, inputs);
  for (Eigen::Index i = 0; i < u.size(); ++i) u.data()[i] = normal(rng);
  return u;
}

}  // namespace

TEST_CASE("mdof2 simulation of displacement, velocity and acceleration outputs matches RK4") {
  const mbgen::test::Mdof2Model model(/*extra_outputs=*/true);  // outputs d1, d2, v1, a2
  const Eigen::VectorXd p = model.info().default_values();
  mbgen::ModelMatrices m;
  model.evaluate(p, m);
  const double dt = 5e-4;
  const int samples = 80;
  const Eigen::MatrixXd u = random_force(samples, 1, 5);
  const mbgen::test::SecondOrderRk4 rk4{m.M, m.C, m.K, m.B};

  for (auto hold : {mbgen::InputHold::ZeroOrder, mbgen::InputHold::FirstOrder}) {
    auto input = [&](int k, double a) {
      if (hold == mbgen::InputHold::ZeroOrder) return Eigen::VectorXd::Constant(1, u(k, 0));
      const double next = k + 1 < samples ? u(k + 1, 0) : 0.0;
      return Eigen::VectorXd::Constant(1, (1 - a) * u(k, 0) + a * next);
    };
    const Eigen::MatrixXd x = rk4.run(input, samples, dt, 1000);
    // Reference outputs from the integrated states: d1 = q1, d2 = q2, v1 = q1', a2 = q2'' from the equation of
    // motion with the input at the sample instant.
    Eigen::MatrixXd reference(samples, 4);
    for (int k = 0; k < samples; ++k) {
      const Eigen::Vector2d q = x.row(k).head(2).transpose(), v = x.row(k).tail(2).transpose();
      const Eigen::Vector2d a = m.M.inverse() * (m.B * u(k, 0) - m.C * v - m.K * q);
      reference.row(k) << q[0], q[1], v[0], a[1];
    }
    const Eigen::MatrixXd y = mbgen::simulate(model, p, u, dt, hold);
    REQUIRE(y.rows() == samples);
    REQUIRE(y.cols() == 4);
    for (Eigen::Index c = 0; c < 4; ++c) {
      INFO("hold " << static_cast<int>(hold) << ", output " << model.info().outputs[static_cast<std::size_t>(c)]);
      CHECK((y.col(c) - reference.col(c)).cwiseAbs().maxCoeff() <= 1e-8 * reference.col(c).cwiseAbs().maxCoeff());
    }
    CHECK(y.row(0).head(3).norm() == 0.0);  // starts at rest
  }
}

namespace {

void check_sensitivities(const mbgen::Model& model, const Eigen::MatrixXd& u, double dt, mbgen::InputHold hold,
                         const Eigen::VectorXd& values = {}) {
  const Eigen::VectorXd p = values.size() > 0 ? values : model.info().default_values();
  const auto result = mbgen::simulate_with_sensitivity(model, p, u, dt, hold);
  const Eigen::MatrixXd plain = mbgen::simulate(model, p, u, dt, hold);
  CHECK((result.outputs - plain).norm() <= 1e-13 * plain.norm());
  REQUIRE(result.doutputs.size() == static_cast<std::size_t>(p.size()));
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    // Fourth-order (Richardson-extrapolated) central differences with a relative step 1e-4: the simulated
    // outputs carry rounding noise ~1e-14 of their size from the matrix exponential, so weak parameters (c22 of
    // mdof2 changes y by ~1e-3 relative) need a step this large, while over hundreds of cycles a mass or
    // stiffness shifts the phase so much that plain central differences would have a truncation error ~1e-5.
    const double h = 1e-4 * std::max(std::abs(p[i]), 1.0);
    auto central = [&](double step) {
      Eigen::VectorXd plus = p, minus = p;
      plus[i] += step;
      minus[i] -= step;
      return Eigen::MatrixXd((mbgen::simulate(model, plus, u, dt, hold) - mbgen::simulate(model, minus, u, dt, hold)) /
                             (2 * step));
    };
    const Eigen::MatrixXd fd = (4 * central(h / 2) - central(h)) / 3;
    const Eigen::MatrixXd& analytic = result.doutputs[static_cast<std::size_t>(i)];
    REQUIRE(analytic.rows() == u.rows());
    INFO("parameter " << model.info().parameters[static_cast<std::size_t>(i)].name << ", hold "
                      << static_cast<int>(hold));
    // Per output column, relative to that column's sensitivity (columns differ by orders of magnitude).
    for (Eigen::Index c = 0; c < analytic.cols(); ++c) {
      const double scale = analytic.col(c).norm() + 1e-12 * plain.col(c).norm() / std::max(std::abs(p[i]), 1.0);
      CHECK((analytic.col(c) - fd.col(c)).norm() <= 1e-6 * scale);
    }
  }
}

}  // namespace

TEST_CASE("mdof2 output sensitivities match central finite differences") {
  const mbgen::test::Mdof2Model model(true);
  const Eigen::MatrixXd u = random_force(300, 1, 9);
  check_sensitivities(model, u, 5e-4, mbgen::InputHold::ZeroOrder);
  check_sensitivities(model, u, 5e-4, mbgen::InputHold::FirstOrder);
}

// Without springs and dampers the transition matrix is [[I, dt I], [0, I]]: defective, with no modal form, so the
// sensitivities are propagated in the original coordinates (the other cases here take the modal route).
TEST_CASE("sensitivities of free, undamped masses, whose transition matrix is defective") {
  const mbgen::test::Mdof2Model model(true);
  Eigen::VectorXd p = model.info().default_values();
  for (int i : {mbgen::test::Mdof2Model::k11, mbgen::test::Mdof2Model::k22, mbgen::test::Mdof2Model::k12,
                mbgen::test::Mdof2Model::c11, mbgen::test::Mdof2Model::c22})
    p[i] = 0;
  const Eigen::MatrixXd u = random_force(300, 1, 10);
  check_sensitivities(model, u, 5e-4, mbgen::InputHold::ZeroOrder, p);
  check_sensitivities(model, u, 5e-4, mbgen::InputHold::FirstOrder, p);
}

TEST_CASE("sensitivities of a random model with every matrix parameter-dependent") {
  const mbgen::test::RandomAffineModel model(4, 2, 3, 10, 21);
  const Eigen::MatrixXd u = random_force(200, 2, 13);
  check_sensitivities(model, u, 4e-3, mbgen::InputHold::ZeroOrder);
  check_sensitivities(model, u, 4e-3, mbgen::InputHold::FirstOrder);
}

TEST_CASE("simulation errors") {
  const mbgen::test::Mdof2Model model;
  const Eigen::VectorXd p = model.info().default_values();
  CHECK_THROWS_WITH(mbgen::simulate(model, p, Eigen::MatrixXd::Zero(10, 2), 1e-3, mbgen::InputHold::ZeroOrder),
                    Catch::Contains("input record has 2 columns, the model has 1 inputs"));
  Eigen::VectorXd massless = p;
  massless[mbgen::test::Mdof2Model::m2] = 0;
  CHECK_THROWS_WITH(mbgen::simulate(model, massless, Eigen::MatrixXd::Zero(10, 1), 1e-3, mbgen::InputHold::ZeroOrder),
                    Catch::Contains("mass matrix M is singular"));
  CHECK_THROWS_WITH(mbgen::simulate_with_sensitivity(model, p, Eigen::MatrixXd::Zero(10, 1), -1e-3,
                                                     mbgen::InputHold::ZeroOrder),
                    Catch::Contains("must be positive"));
  CHECK(mbgen::simulate(model, p, Eigen::MatrixXd::Zero(0, 1), 1e-3, mbgen::InputHold::ZeroOrder).rows() == 0);
}

TEST_CASE("steady-state sinusoidal response agrees with the FRF") {
  // One degree of freedom, 50 Hz, zeta 0.2 (transients decay within ~0.1 s), driven at 40 Hz for 1 s. The FOH
  // interpolates the sampled sine linearly, an error of about (w dt)^2 / 8 ~ 1.6e-4 relative at 10 kHz.
  const double pi = std::acos(-1.0), w0 = 2 * pi * 50, zeta = 0.2, f = 40, dt = 1e-4;
  mbgen::ModelMatrices m;
  m.M = Eigen::MatrixXd::Constant(1, 1, 1.0);
  m.C = Eigen::MatrixXd::Constant(1, 1, 2 * zeta * w0);
  m.K = Eigen::MatrixXd::Constant(1, 1, w0 * w0);
  m.B = Eigen::MatrixXd::Ones(1, 1);
  m.Cd = Eigen::MatrixXd::Ones(1, 1);
  m.Cv = Eigen::MatrixXd::Zero(1, 1);
  m.Ca = Eigen::MatrixXd::Zero(1, 1);
  const int samples = 10000;
  Eigen::MatrixXd u(samples, 1);
  for (int k = 0; k < samples; ++k) u(k, 0) = std::sin(2 * pi * f * k * dt);
  const Eigen::MatrixXd y = mbgen::simulate(m, u, dt, mbgen::InputHold::FirstOrder);
  // The FRF route: closed form 1 / (k - w^2 m + j w c), independent of frf.cpp.
  const double w = 2 * pi * f;
  const std::complex<double> H = 1.0 / std::complex<double>(w0 * w0 - w * w, w * 2 * zeta * w0);
  double worst = 0;
  for (int k = samples - 500; k < samples; ++k) {
    const double expected = std::imag(H * std::exp(std::complex<double>(0, w * k * dt)));
    worst = std::max(worst, std::abs(y(k, 0) - expected));
  }
  CHECK(worst <= 1e-3 * std::abs(H));
}
