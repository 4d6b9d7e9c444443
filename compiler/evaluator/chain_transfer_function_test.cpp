// At machine scale (issue 14): the run-time transfer-function routine (mbgen/transfer_function.hpp, what the
// generated code calls for blocks too large for symbolic coefficients) against the exact rational coefficients of
// the derivation, on a chain of 16 six-coordinate bodies (one 96-coordinate block, polynomials of degree 192).
// In long double: in double these coefficients do not exist (a_0, the product of the squared natural frequencies,
// is about 1e630; the routine's det K overflows first), so at this size the run time needs another form than
// polynomial coefficients (issue 14, item 3). Measured: 1.0e-13 and 9.8e-14 of the largest scaled coefficient.
#include <catch2/catch.hpp>

#include <cln/integer.h>
#include <cln/rational.h>

#include <chrono>
#include <cmath>

#include "frontend/parser.hpp"
#include "mbgen/transfer_function.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/test_chain_model.hpp"
#include "symbolic/test_support.hpp"

using namespace mbgen;
using namespace mbgen::symbolic;
using namespace mbgen::symbolic::test;

namespace {

template <typename Scalar>
DenseMatrix<Scalar> dense(const GiNaC::matrix& m, const GiNaC::exmap& values) {
  DenseMatrix<Scalar> r(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j)
      r(i, j) = m(i, j).is_zero() ? Scalar(0) : static_cast<Scalar>(to_double(m(i, j), values));
  return r;
}

// Largest error of the run-time coefficients, each as |c_k - exact_k| rho^k over max_j |exact_j| rho^j (the measure
// of the generated-code tests), rho about a_0^(1/degree).
template <typename Scalar>
double relative_error(const SymbolicModel& sm, const TransferFunction& tf) {
  const GiNaC::exmap values = sm.values();
  TransferFunctionSystem<Scalar> sys;
  sys.M = dense<Scalar>(sm.M, values);
  sys.C = dense<Scalar>(sm.C_total, values);
  sys.K = dense<Scalar>(sm.K, values);
  const auto o = static_cast<unsigned>(tf.output), u = static_cast<unsigned>(tf.input);
  sys.b = dense<Scalar>(sm.B, values).col(u);
  sys.cd = dense<Scalar>(sm.Cd, values).row(o);
  sys.cv = dense<Scalar>(sm.Cv, values).row(o);
  sys.ca = dense<Scalar>(sm.Ca, values).row(o);
  const TransferFunctionCoefficients<Scalar> got = transfer_function_coefficients(sys, tf.coordinates);
  // In logarithms: a_0 ~ 1e600 and rho^192 overflow a double. log |x rho^(k - degree)|, the sign apart.
  const int degree = static_cast<int>(tf.denominator.size()) - 1;
  auto log_abs = [](const GiNaC::ex& x) { return static_cast<long double>(to_double(GiNaC::log(GiNaC::abs(x)))); };
  const long double log_rho = log_abs(tf.denominator[0]) / degree;
  auto scaled_exact = [&](const GiNaC::ex& x, std::size_t k) -> long double {
    if (x.is_zero()) return 0;
    const long double v = std::exp(log_abs(x) + (static_cast<long double>(k) - degree) * log_rho);
    return to_double(x) < 0 || (GiNaC::is_a<GiNaC::numeric>(x) && GiNaC::ex_to<GiNaC::numeric>(x).is_negative()) ? -v : v;
  };
  auto scaled_got = [&](Scalar x, std::size_t k) -> long double {
    const long double ax = std::fabs(static_cast<long double>(x));
    if (ax == 0) return 0;
    const long double v = std::exp(std::log(ax) + (static_cast<long double>(k) - degree) * log_rho);
    return x < 0 ? -v : v;
  };
  double worst = 0;
  auto check = [&](const std::vector<Scalar>& c, const std::vector<GiNaC::ex>& exact) {
    REQUIRE(c.size() >= exact.size());
    std::vector<long double> e(c.size(), 0), g(c.size());
    long double scale = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (k < exact.size()) e[k] = scaled_exact(exact[k], k);
      g[k] = scaled_got(c[k], k);
      scale = std::max(scale, std::fabs(e[k]));
    }
    for (std::size_t k = 0; k < c.size(); ++k) {
      const long double err = std::fabs(g[k] - e[k]) / scale;
      worst = std::isfinite(static_cast<double>(err)) ? std::max(worst, static_cast<double>(err)) : HUGE_VAL;
    }
  };
  check(got.numerator, tf.numerator);
  check(got.denominator, tf.denominator);
  return worst;
}

}  // namespace

// "slow": skipped by the sanitizer pass, where this file is compiled at -O0 and its 386 long double complex LU
// factorizations of order 97 (Eigen, header-only) run tens of times slower; the libraries it tests are covered there by
// pencil_determinants_test and transfer_functions_test.
TEST_CASE("chain of 16 bodies: exact transfer functions, and the run-time routine meets them (slow at -O0)") {
  const ir::ModelIr model = frontend::parse_string(chain_model_text(16), "chain16.mdl");
  const auto start = std::chrono::steady_clock::now();
  const SymbolicModel sm = derive(model);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  INFO("derive with transfer functions: " << seconds << " s");
  REQUIRE(sm.transfer_functions.size() == 2);
  for (const TransferFunction& tf : sm.transfer_functions) {
    REQUIRE(tf.exact);
    REQUIRE_FALSE(tf.symbolic);
    REQUIRE(tf.coordinates.size() == 96);
    REQUIRE(tf.denominator.size() == 193);
    CHECK(tf.denominator.back() == 1);
    for (const GiNaC::ex& c : tf.denominator) CHECK(GiNaC::is_a<GiNaC::numeric>(c));
    const double error = relative_error<long double>(sm, tf);
    INFO(model.outputs[static_cast<std::size_t>(tf.output)].name << ": long double error " << error);
    CHECK(error <= 1e-11);
  }
  CHECK(sm.cancellations.empty());
}
