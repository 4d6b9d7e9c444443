// The output-error residuals and their Jacobians (output_error.hpp): the excited-block reduction against the
// dynamics library on the full model, and the Jacobians against central finite differences of the residuals.
#include "excited_block.hpp"
#include "output_error.hpp"
#include "mbgen_test/estimation.hpp"
#include "mbgen_test/finite_difference.hpp"

#include "mbgen/dynamics/frf.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace mbgen;
using test::LinearModel;

namespace {

// Two chains that do not touch: q0-q1-q2 (driven by u0, measured by y0, y1) and q3-q4 (driven by u1, measured by
// y1 through a velocity term). Parameter "link" multiplies a spring between q2 and q3 whose value is 0 at the
// prior: its derivative couples the chains, so the reduction must keep both for the Jacobian.
LinearModel two_chains() {
  using R = ParameterRole;
  LinearModel m("chains", 5, {"u0", "u1"}, {"y0", "y1"});
  std::vector<int> mass, spring, damper;
  for (int q = 0; q < 5; ++q) {
    mass.push_back(m.parameter("m" + std::to_string(q), 1.0 + 0.3 * q, R::Estimate));
    m.linear(LinearModel::M, mass.back(), q, q, 1);
    spring.push_back(m.parameter("k" + std::to_string(q), 1e4 * (1 + 0.5 * q), R::Estimate));
    damper.push_back(m.parameter("c" + std::to_string(q), 2.0 + q, R::Estimate));
    const int neighbour = (q == 0 || q == 3) ? -1 : q - 1;
    m.element(LinearModel::K, spring.back(), q, neighbour);
    m.element(LinearModel::C, damper.back(), q, neighbour);
  }
  const int link = m.parameter("link", 0.0, R::Estimate, -1e9, 1e9);
  m.element(LinearModel::K, link, 2, 3);
  const int gain = m.parameter("gain", 2.0, R::Estimate);
  m.linear(LinearModel::B, gain, 0, 0, 1);
  m.constant(LinearModel::B, 4, 1, 1);
  m.constant(LinearModel::Cd, 0, 2, 1);
  m.constant(LinearModel::Cd, 1, 1, 0.5);
  const int sensor = m.parameter("sensor", 0.1, R::Estimate);
  m.linear(LinearModel::Cv, sensor, 1, 4, 1);
  return m;
}

std::vector<int> all_parameters(const Model& model) {
  std::vector<int> p(model.info().parameters.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<int>(i);
  return p;
}

}  // namespace

TEST_CASE("the excited block gives the full model's FRF and Jacobian", "[response][frf]") {
  const LinearModel model = two_chains();
  const Eigen::VectorXd p = model.info().default_values();
  ModelMatrices m;
  ModelDerivatives d;
  model.evaluate(p, m);
  model.derivatives(p, d);
  const int np = static_cast<int>(p.size());
  const std::vector<double> f = {0.7, 5.0, 13.0, 31.0};
  const FrfJacobianResult full = frf_jacobian(m, d, np, f);
  std::vector<int> column(static_cast<std::size_t>(np));
  for (int j = 0; j < np; ++j) column[static_cast<std::size_t>(j)] = j;

  SECTION("input u0 with derivatives: the link keeps both chains") {
    const estimation::ReducedModel red = estimation::reduce_to_excited_block(m, &d, {0}, {0, 1}, column);
    CHECK(red.coordinates.size() == 5);
  }
  SECTION("input u1 without the link: only q3, q4") {
    std::vector<int> no_link = column;
    no_link[static_cast<std::size_t>(model.info().parameter_index("link"))] = -1;
    ModelDerivatives d_without = d;
    d_without.K.erase(std::remove_if(d_without.K.begin(), d_without.K.end(),
                                     [&](const DerivativeEntry& e) { return e.param == model.info().parameter_index("link"); }),
                      d_without.K.end());
    const estimation::ReducedModel red = estimation::reduce_to_excited_block(m, &d_without, {1}, {1}, no_link);
    REQUIRE(red.coordinates == std::vector<int>{3, 4});
    const FrfJacobianResult small = frf_jacobian(red.m, red.d, np, f);
    for (std::size_t k = 0; k < f.size(); ++k) {
      const std::complex<double> ref = full.H[k](1, 1);
      CHECK(std::abs(small.H[k](0, 0) - ref) <= 1e-12 * std::abs(ref));
      for (int j = 0; j < np; ++j) {
        if (j == model.info().parameter_index("link")) continue;
        const std::complex<double> dref = full.derivative(k, j)(1, 1);
        CHECK(std::abs(small.derivative(k, j)(0, 0) - dref) <= 1e-9 * (std::abs(dref) + std::abs(ref)));
      }
    }
  }
  SECTION("input u0, output y0: values and every derivative match, dropped columns are absent") {
    std::vector<int> some(static_cast<std::size_t>(np), -1);
    some[0] = 0;  // m0
    some[static_cast<std::size_t>(model.info().parameter_index("link"))] = 1;
    some[static_cast<std::size_t>(model.info().parameter_index("gain"))] = 2;
    some[static_cast<std::size_t>(model.info().parameter_index("k4"))] = 3;
    const estimation::ReducedModel red = estimation::reduce_to_excited_block(m, &d, {0}, {0}, some);
    const FrfJacobianResult small = frf_jacobian(red.m, red.d, 4, f);
    for (std::size_t k = 0; k < f.size(); ++k) {
      const std::complex<double> ref = full.H[k](0, 0);
      CHECK(std::abs(small.H[k](0, 0) - ref) <= 1e-12 * std::abs(ref));
      for (int j = 0; j < np; ++j) {
        const int c = some[static_cast<std::size_t>(j)];
        if (c < 0) continue;
        const std::complex<double> dref = full.derivative(k, j)(0, 0);
        CHECK(std::abs(small.derivative(k, c)(0, 0) - dref) <= 1e-9 * (std::abs(dref) + std::abs(ref)));
      }
      CHECK(std::abs(small.derivative(k, 1)(0, 0)) > 0);  // the link matters at first order
    }
  }
}

namespace {

// Central differences of the residuals in physical units, column by column.
Eigen::MatrixXd finite_difference_jacobian(const estimation::OutputErrorProblem& problem, const Eigen::VectorXd& p,
                                           const std::vector<int>& free, estimation::ResidualKind kind) {
  const auto residuals = [&](const Eigen::VectorXd& q) {
    Eigen::VectorXd r;
    problem.evaluate(q, free, kind, r, nullptr);
    return r;
  };
  // Relative steps; a parameter at 0 (the link spring) gets the stiffnesses' order of magnitude.
  return test::central_difference_jacobian(residuals, p, free, [](double v) { return 1e-6 * (v != 0 ? std::abs(v) : 1e4); });
}

void check_against_differences(const estimation::OutputErrorProblem& problem, const Eigen::VectorXd& p,
                               const std::vector<int>& free, estimation::ResidualKind kind, double tolerance) {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  problem.evaluate(p, free, kind, r, &J);
  const Eigen::MatrixXd fd = finite_difference_jacobian(problem, p, free, kind);
  REQUIRE(J.rows() == fd.rows());
  for (Eigen::Index j = 0; j < J.cols(); ++j) {
    INFO("column " << j);
    const double scale = fd.col(j).cwiseAbs().maxCoeff() + J.col(j).cwiseAbs().maxCoeff();
    CHECK((J.col(j) - fd.col(j)).cwiseAbs().maxCoeff() <= tolerance * scale + 1e-300);
  }
}

}  // namespace

TEST_CASE("FRF residual Jacobians agree with finite differences", "[response][frf]") {
  const LinearModel model = two_chains();
  const Eigen::VectorXd p = model.info().default_values();
  FrfData data;
  data.file = "chains.csv";
  data.f_hz = Eigen::VectorXd::LinSpaced(40, 1.0, 40.0);
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  for (const auto& [out, in] : {std::pair<std::string, std::string>{"y0", "u0"}, {"y1", "u0"}, {"y1", "u1"}}) {
    FrfChannel c;
    c.output = out;
    c.input = in;
    c.values.resize(data.f_hz.size());
    for (Eigen::Index k = 0; k < c.values.size(); ++k) c.values[k] = {1e-4 * (1 + normal(rng)), 1e-4 * normal(rng)};
    data.channels.push_back(c);
  }
  const estimation::OutputErrorProblem problem(model, {DataSet(data)}, FrfWeighting{});
  const std::vector<int> free = all_parameters(model);
  check_against_differences(problem, p, free, estimation::ResidualKind::Weighted, 1e-6);
  check_against_differences(problem, p, free, estimation::ResidualKind::LogRatio, 1e-6);

  // A parameter a data set sets itself gets a zero column.
  data.set["k1"].value = 2e4;
  const estimation::OutputErrorProblem with_set(model, {DataSet(data)}, FrfWeighting{});
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  with_set.evaluate(p, free, estimation::ResidualKind::Weighted, r, &J);
  CHECK(J.col(model.info().parameter_index("k1")).isZero(0));
  CHECK_FALSE(J.col(model.info().parameter_index("k2")).isZero(0));
}

TEST_CASE("time residual Jacobians agree with finite differences", "[response][time]") {
  const LinearModel model = two_chains();
  const Eigen::VectorXd p = model.info().default_values();
  for (const HoldMode hold : {HoldMode::ZeroOrder, HoldMode::None}) {
    INFO((hold == HoldMode::None ? "first-order hold" : "zero-order hold"));
    TimeRecord record;
    record.file = "chains-time.csv";
    record.hold = hold;
    const Eigen::Index N = 200;
    record.t = Eigen::VectorXd::LinSpaced(N, 0, 2e-3 * double(N - 1));
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    for (const char* name : {"u0", "u1", "y0", "y1"}) {
      Eigen::VectorXd v(N);
      for (Eigen::Index k = 0; k < N; ++k) v[k] = (name[0] == 'u' ? 10.0 : 1e-3) * normal(rng);
      record.signals.push_back({name, v});
    }
    const estimation::OutputErrorProblem problem(model, {DataSet(record)}, FrfWeighting{});
    check_against_differences(problem, p, all_parameters(model), estimation::ResidualKind::Weighted, 1e-5);
  }
}
