// The estimator's FRF and time responses (model_response.hpp) against the dynamics library's independent
// implementations (frf.hpp, simulate.hpp) and against central finite differences, on random affine models
// that exercise all seven matrices.
#include "model_response.hpp"

#include "../dynamics/test_models.hpp"
#include "mbgen/frf.hpp"
#include "mbgen/simulate.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace mbgen;

TEST_CASE("estimator FRF and Jacobian agree with the dynamics library", "[response][frf]") {
  const test::RandomAffineModel model(4, 2, 3, 9, 17);
  const Eigen::VectorXd p = model.info().default_values();
  ModelMatrices m;
  model.evaluate(p, m);
  ModelDerivatives d;
  model.derivatives(p, d);
  const std::vector<double> f = {0.5, 3.0, 7.5, 12.0, 40.0};
  const Eigen::VectorXd f_hz = Eigen::Map<const Eigen::VectorXd>(f.data(), 5);
  std::vector<estimation::ChannelIndex> channels;
  for (int o = 0; o < 3; ++o)
    for (int i = 0; i < 2; ++i) channels.push_back({o, i});
  std::vector<int> params(9);
  for (int j = 0; j < 9; ++j) params[static_cast<std::size_t>(j)] = j;
  const estimation::FrfResponse mine = estimation::frf_response(m, &d, params, {}, f_hz, channels);
  const FrfJacobianResult theirs = frf_jacobian(m, d, 9, f);
  for (std::size_t c = 0; c < channels.size(); ++c)
    for (std::size_t k = 0; k < f.size(); ++k) {
      const auto o = channels[c].output, i = channels[c].input;
      const auto ki = static_cast<Eigen::Index>(k);
      CHECK(std::abs(mine.values[c][ki] - theirs.H[k](o, i)) <= 1e-12 * std::abs(theirs.H[k](o, i)) + 1e-300);
      for (int j = 0; j < 9; ++j) {
        const std::complex<double> ref = theirs.derivative(k, j)(o, i);
        CHECK(std::abs(mine.jacobian[c](ki, j) - ref) <= 1e-9 * (std::abs(ref) + std::abs(theirs.H[k](o, i))));
      }
    }
  // A parameter marked inactive (a data set's `# set`) gets a zero column.
  const estimation::FrfResponse masked = estimation::frf_response(m, &d, params, {3}, f_hz, channels);
  CHECK(masked.jacobian[0].col(3).isZero(0));
  CHECK(masked.jacobian[0].col(2) == mine.jacobian[0].col(2));
}

TEST_CASE("estimator time response and sensitivities agree with the dynamics library and finite differences",
          "[response][time]") {
  const test::RandomAffineModel model(3, 2, 2, 6, 5);
  const Eigen::VectorXd p = model.info().default_values();
  ModelMatrices m;
  model.evaluate(p, m);
  ModelDerivatives d;
  model.derivatives(p, d);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd u(300, 2);
  for (Eigen::Index i = 0; i < u.size(); ++i) u.data()[i] = normal(rng);
  const double dt = 2e-3;
  std::vector<int> params(6);
  for (int j = 0; j < 6; ++j) params[static_cast<std::size_t>(j)] = j;
  for (const HoldMode hold : {HoldMode::ZeroOrder, HoldMode::None}) {
    INFO((hold == HoldMode::None ? "first-order hold" : "zero-order hold"));
    const std::vector<estimation::DenseDerivative> dd = estimation::dense_derivatives(m, d, params);
    const estimation::TimeResponse mine = estimation::time_response(m, &dd, u, dt, hold, {0, 1});
    const SimulationSensitivity theirs = simulate_with_sensitivity(
        m, d, 6, u, dt, hold == HoldMode::None ? InputHold::FirstOrder : InputHold::ZeroOrder);
    for (int o = 0; o < 2; ++o) {
      const double scale = theirs.outputs.col(o).cwiseAbs().maxCoeff();
      CHECK((mine.values[static_cast<std::size_t>(o)] - theirs.outputs.col(o)).cwiseAbs().maxCoeff() <= 1e-9 * scale);
      for (int j = 0; j < 6; ++j) {
        const Eigen::VectorXd ref = theirs.doutputs[static_cast<std::size_t>(j)].col(o);
        const double s = ref.cwiseAbs().maxCoeff() + 1e-30;
        CHECK((mine.sensitivity[static_cast<std::size_t>(o)].col(j) - ref).cwiseAbs().maxCoeff() <= 1e-7 * s);
      }
    }
    // Central differences on the parameter output 1 is most sensitive to.
    Eigen::Index j = 0;
    mine.sensitivity[1].colwise().norm().maxCoeff(&j);
    const double h = 1e-6;
    Eigen::VectorXd pp = p, pm = p;
    pp[j] += h;
    pm[j] -= h;
    ModelMatrices mp, mm;
    model.evaluate(pp, mp);
    model.evaluate(pm, mm);
    const Eigen::VectorXd fd = (estimation::time_response(mp, nullptr, u, dt, hold, {1}).values[0] -
                                estimation::time_response(mm, nullptr, u, dt, hold, {1}).values[0]) / (2 * h);
    REQUIRE(fd.cwiseAbs().maxCoeff() > 0);
    CHECK((mine.sensitivity[1].col(j) - fd).cwiseAbs().maxCoeff() <= 1e-5 * fd.cwiseAbs().maxCoeff());
  }
}
