// mdof2 (docs/reference-models.md): the derived transfer functions against the closed-form coefficients, the thesis's
// printed Eq. 5.19, and the modes of Table 5.1.
#include <catch2/catch.hpp>

#include <cmath>

#include "symbolic/derive.hpp"
#include "symbolic/test_support.hpp"

using namespace mbgen;
using namespace mbgen::symbolic;
using namespace mbgen::symbolic::test;

namespace {

const TransferFunction& tf_of(const SymbolicModel& sm, const std::string& output, const std::string& input) {
  for (const TransferFunction& tf : sm.transfer_functions)
    if (sm.model->outputs[tf.output].name == output && sm.model->inputs[tf.input].name == input) return tf;
  throw std::runtime_error("no transfer function " + output + "/" + input);
}

// Rounds x to `digits` significant digits, as the thesis prints them.
double round_significant(double x, int digits) {
  const double scale = std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::fabs(x)))));
  return std::round(x * scale) / scale;
}

}  // namespace

TEST_CASE("mdof2: matrices are the textbook two-mass matrices") {
  const ir::ModelIr model = load_example("mdof2");
  const SymbolicModel sm = derive(model);
  const GiNaC::ex m1 = symbol_of(sm, "m1"), m2 = symbol_of(sm, "m2"), k11 = symbol_of(sm, "k11"),
                  k12 = symbol_of(sm, "k12"), k22 = symbol_of(sm, "k22"), c11 = symbol_of(sm, "c11"),
                  c12 = symbol_of(sm, "c12"), c22 = symbol_of(sm, "c22");
  REQUIRE(sm.coordinates.size() == 2);
  CHECK(sm.coordinates[0].name() == "mass1.x");
  CHECK(sm.coordinates[1].name() == "mass2.x");
  CHECK(same(sm.M, GiNaC::matrix{{m1, 0}, {0, m2}}));
  CHECK(same(sm.K, GiNaC::matrix{{k11 + k12, -k12}, {-k12, k22 + k12}}));
  CHECK(same(sm.C, GiNaC::matrix{{c11 + c12, -c12}, {-c12, c22 + c12}}));
  CHECK(same(sm.G, GiNaC::matrix(2, 2)));
  CHECK(same(sm.B, GiNaC::matrix{{1}, {0}}));
  CHECK(same(sm.Cd, GiNaC::matrix{{1, 0}, {0, 1}}));
  REQUIRE(sm.blocks.size() == 1);
  CHECK(sm.blocks[0] == std::vector<int>{0, 1});
  CHECK(sm.cancellations.empty());
}

TEST_CASE("mdof2: G11 and G21 equal the closed-form coefficients exactly") {
  const ir::ModelIr model = load_example("mdof2");
  const SymbolicModel sm = derive(model);
  const GiNaC::ex m1 = symbol_of(sm, "m1"), m2 = symbol_of(sm, "m2"), k11 = symbol_of(sm, "k11"),
                  k12 = symbol_of(sm, "k12"), k22 = symbol_of(sm, "k22"), c11 = symbol_of(sm, "c11"),
                  c12 = symbol_of(sm, "c12"), c22 = symbol_of(sm, "c22");
  const GiNaC::ex mm = m1 * m2;
  const std::vector<GiNaC::ex> denominator = {
      (k11 * k12 + k11 * k22 + k12 * k22) / mm,
      (c11 * k12 + c11 * k22 + c12 * k11 + c12 * k22 + c22 * k11 + c22 * k12) / mm,
      (c11 * c12 + c11 * c22 + c12 * c22 + k11 * m2 + k12 * m1 + k12 * m2 + k22 * m1) / mm,
      (c11 * m2 + c12 * m1 + c12 * m2 + c22 * m1) / mm,
      1};
  const TransferFunction& g11 = tf_of(sm, "d1", "F1");
  CHECK(g11.symbolic);
  CHECK(g11.coordinates == std::vector<int>{0, 1});
  REQUIRE(g11.denominator.size() == 5);
  for (size_t k = 0; k < 5; ++k) CHECK(same(g11.denominator[k], denominator[k]));
  REQUIRE(g11.numerator.size() == 3);
  CHECK(same(g11.numerator[0], (k12 + k22) / mm));
  CHECK(same(g11.numerator[1], (c12 + c22) / mm));
  CHECK(same(g11.numerator[2], 1 / m1));  // the thesis's Eq. 5.8c prints 1/m2: a typo

  const TransferFunction& g21 = tf_of(sm, "d2", "F1");
  REQUIRE(g21.denominator.size() == 5);
  for (size_t k = 0; k < 5; ++k) CHECK(same(g21.denominator[k], denominator[k]));
  REQUIRE(g21.numerator.size() == 2);
  CHECK(same(g21.numerator[0], k12 / mm));
  CHECK(same(g21.numerator[1], c12 / mm));
  // Output-major order.
  REQUIRE(sm.transfer_functions.size() == 2);
  CHECK(sm.transfer_functions[0].output == 0);
  CHECK(sm.transfer_functions[1].output == 1);
}

TEST_CASE("mdof2: the values behind the thesis's Eq. 5.19 reproduce every printed digit") {
  const ir::ModelIr model = load_example("mdof2");
  DeriveOptions options;
  options.set = {{"m1", "1.39"}, {"m2", "1.09"}, {"k11", "2.0e6"}, {"k12", "0.04e6"}, {"k22", "0.20e6"},
                 {"c11", "18"},  {"c22", "8"},   {"c12", "0"}};
  const SymbolicModel sm = derive(model, options);
  CHECK(sm.parameters[sm.parameter_index("k12")].value == GiNaC::numeric(40000));
  const GiNaC::exmap values = sm.values();
  const TransferFunction& g11 = tf_of(sm, "d1", "F1");
  const auto at = [&](const GiNaC::ex& e) { return to_double(e, values); };
  // G11 = (0.72 s^2 + 5.28 s + 158405.39)/(s^4 + 20.29 s^3 + 1687904.43 s^2 + 1.36e7 s + 3.22e11)
  CHECK(std::round(at(g11.numerator[2]) * 100) / 100 == Approx(0.72).epsilon(1e-12));
  CHECK(std::round(at(g11.numerator[1]) * 100) / 100 == Approx(5.28).epsilon(1e-12));
  CHECK(std::round(at(g11.numerator[0]) * 100) / 100 == Approx(158405.39).epsilon(1e-12));
  CHECK(std::round(at(g11.denominator[3]) * 100) / 100 == Approx(20.29).epsilon(1e-12));
  CHECK(std::round(at(g11.denominator[2]) * 100) / 100 == Approx(1687904.43).epsilon(1e-12));
  CHECK(round_significant(at(g11.denominator[1]), 3) == Approx(1.36e7).epsilon(1e-12));
  CHECK(round_significant(at(g11.denominator[0]), 3) == Approx(3.22e11).epsilon(1e-12));
  CHECK(g11.denominator[4] == 1);
}

TEST_CASE("mdof2: Table 5.1 values give the modes 166.29 Hz and 89.72 Hz") {
  const ir::ModelIr model = load_example("mdof2");
  const SymbolicModel sm = derive(model, {{}, false});
  CHECK(sm.transfer_functions.empty());
  const GiNaC::exmap values = sm.values();
  const Eigen::MatrixXd M = to_eigen(sm.M, values), C = to_eigen(sm.C_total, values), K = to_eigen(sm.K, values);
  // State space x = [q; q'], x' = A x.
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
  A.topRightCorner(2, 2) = Eigen::MatrixXd::Identity(2, 2);
  A.bottomLeftCorner(2, 2) = -M.inverse() * K;
  A.bottomRightCorner(2, 2) = -M.inverse() * C;
  const Eigen::VectorXcd lambda = A.eigenvalues();
  std::vector<std::pair<double, double>> modes;  // (f_hz, zeta) for the eigenvalues with positive imaginary part
  for (int i = 0; i < 4; ++i)
    if (lambda[i].imag() > 0)
      modes.emplace_back(std::abs(lambda[i]) / (2 * M_PI), -lambda[i].real() / std::abs(lambda[i]));
  std::sort(modes.begin(), modes.end());
  REQUIRE(modes.size() == 2);
  CHECK(std::round(modes[0].first * 100) / 100 == Approx(89.72).epsilon(1e-12));
  CHECK(std::round(modes[1].first * 100) / 100 == Approx(166.29).epsilon(1e-12));
  CHECK(round_significant(modes[0].second, 3) == Approx(0.000514).epsilon(1e-12));
  CHECK(round_significant(modes[1].second, 3) == Approx(0.00455).epsilon(1e-12));
}
