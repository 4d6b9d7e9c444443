// The generated C++ at 256-bit precision (mpfr::mpreal, Debian libmpfrc++-dev) against the exact rationals of the
// symbolic engine. Double-precision comparisons cannot tell `Scalar(1)/Scalar(3)` from a double literal 0.333...;
// here every matrix entry and every Jacobian value must agree with the exact result to ~70 digits, so a constant
// rounded to double anywhere in the emitted code (or integer division) fails the test.
#include <catch2/catch.hpp>

#include <mpreal.h>

#include <random>
#include <sstream>
#include <string>

#define MBGEN_GENERATED_TEMPLATES_ONLY
#include "mdof2_model.cpp"
#include "spindle_model.cpp"
#include "spindle_spin_model.cpp"
#undef MBGEN_GENERATED_TEMPLATES_ONLY

#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"

namespace {

using mpfr::mpreal;
constexpr int bits = 256;
const double tolerance = 1e-70;  // 256 bits carry ~77 decimal digits

// An exact value as a 256-bit number. Rationals: numerator and denominator are exact integers, one rounding in the
// division. Anything else (Pi in the gyroscopic terms) is evaluated by CLN to 100 digits first.
mpreal to_mpreal(const GiNaC::ex& e) {
  GiNaC::ex value = e;
  if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_rational()) {
    const long saved = GiNaC::Digits;
    GiNaC::Digits = 100;
    value = GiNaC::evalf(e);
    GiNaC::Digits = saved;
  }
  REQUIRE(GiNaC::is_a<GiNaC::numeric>(value));
  const GiNaC::numeric q = GiNaC::ex_to<GiNaC::numeric>(value);
  REQUIRE(q.is_real());
  std::ostringstream num, den;
  if (!q.is_rational()) {
    num << q;  // CLN's float syntax: digits, optional exponent "E"
    std::string text = num.str();
    for (char& c : text)
      if (c == 'E') c = 'e';
    return mpreal(text, bits);
  }
  num << q.numer();
  den << q.denom();
  return mpreal(num.str(), bits) / mpreal(den.str(), bits);
}

struct Derived {
  mbgen::ir::ModelIr ir;
  mbgen::symbolic::SymbolicModel sm;
  explicit Derived(const std::string& path) : ir(mbgen::frontend::parse_file(path)), sm(mbgen::symbolic::derive(ir)) {}
};

// Exact random values near the defaults, with denominators (7, 11, 13) that have no finite binary expansion.
GiNaC::exmap random_values(const mbgen::symbolic::SymbolicModel& sm, std::mt19937& rng) {
  std::uniform_int_distribution<int> u(700, 1300);
  const int denominators[] = {7 * 100, 11 * 100, 13 * 100};
  GiNaC::exmap m;
  int k = 0;
  for (const auto& p : sm.parameters) {
    const GiNaC::numeric factor(u(rng), denominators[k++ % 3]);
    m[p.sym] = p.value.is_zero() ? GiNaC::ex(factor / 7) : p.value * factor;
  }
  return m;
}

// Largest |generated - exact| over the largest |exact| of one matrix.
template <typename Matrix>
double relative_error(const Matrix& generated, const GiNaC::matrix& symbolic, const GiNaC::exmap& values) {
  REQUIRE(static_cast<unsigned>(generated.rows()) == symbolic.rows());
  REQUIRE(static_cast<unsigned>(generated.cols()) == symbolic.cols());
  mpreal scale(0, bits), error(0, bits);
  for (unsigned r = 0; r < symbolic.rows(); ++r)
    for (unsigned c = 0; c < symbolic.cols(); ++c) {
      const mpreal exact = to_mpreal(symbolic(r, c).subs(values));
      scale = mpfr::max(scale, mpfr::abs(exact));
      error = mpfr::max(error, mpfr::abs(generated(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) - exact));
    }
  return scale == 0 ? error.toDouble() : (error / scale).toDouble();
}

// Every sparse Jacobian value against the exact derivative of its matrix entry.
template <typename Pattern>
double jacobian_error(const Pattern& pattern, void (*jacobian)(const mpreal*, mpreal*), const std::vector<mpreal>& p,
                      const GiNaC::matrix& symbolic, const Derived& d, const GiNaC::exmap& values) {
  std::vector<mpreal> computed(pattern.size() + 1, mpreal(0, bits));
  jacobian(p.data(), computed.data());
  double worst = 0;
  for (std::size_t k = 0; k < pattern.size(); ++k) {
    const auto& e = pattern[k];
    const GiNaC::symbol& s = d.sm.parameters[static_cast<std::size_t>(e.param)].sym;
    const mpreal exact = to_mpreal(symbolic(static_cast<unsigned>(e.row), static_cast<unsigned>(e.col)).diff(s).subs(values));
    const mpreal scale = mpfr::max(mpfr::abs(exact), mpreal(1e-300, bits));
    worst = std::max(worst, (mpfr::abs(computed[k] - exact) / scale).toDouble());
  }
  return worst;
}

#define CHECK_GENERATED_AT_HIGH_PRECISION(NS, PATH)                                                          \
  do {                                                                                                       \
    namespace g = generated::NS;                                                                             \
    mpreal::set_default_prec(bits);                                                                          \
    Derived d(PATH);                                                                                         \
    REQUIRE(static_cast<int>(d.sm.parameters.size()) == g::num_parameters);                                  \
    std::mt19937 rng(2024);                                                                                  \
    for (int trial = 0; trial < 3; ++trial) {                                                                \
      const GiNaC::exmap values = random_values(d.sm, rng);                                                  \
      std::vector<mpreal> p;                                                                                 \
      for (const auto& fp : d.sm.parameters) p.push_back(to_mpreal(values.at(fp.sym)));                      \
      g::CoordinateMatrix<mpreal> M, C, G, K;                                                                \
      g::InputMatrix<mpreal> B;                                                                              \
      g::OutputMatrix<mpreal> Cd, Cv, Ca;                                                                    \
      g::mass_matrix(p.data(), M), g::damping_matrix(p.data(), C), g::gyroscopic_matrix(p.data(), G);        \
      g::stiffness_matrix(p.data(), K), g::input_matrix(p.data(), B);                                        \
      g::output_displacement_matrix(p.data(), Cd), g::output_velocity_matrix(p.data(), Cv);                  \
      g::output_acceleration_matrix(p.data(), Ca);                                                           \
      INFO("trial " << trial);                                                                               \
      CHECK(relative_error(M, d.sm.M, values) < tolerance);                                                  \
      CHECK(relative_error(C, d.sm.C_total, values) < tolerance);                                                 \
      CHECK(relative_error(G, d.sm.G, values) < tolerance);                                                  \
      CHECK(relative_error(K, d.sm.K, values) < tolerance);                                                  \
      CHECK(relative_error(B, d.sm.B, values) < tolerance);                                                  \
      CHECK(relative_error(Cd, d.sm.Cd, values) < tolerance);                                                \
      CHECK(relative_error(Cv, d.sm.Cv, values) < tolerance);                                                \
      CHECK(relative_error(Ca, d.sm.Ca, values) < tolerance);                                                \
      CHECK(jacobian_error(g::mass_matrix_jacobian_pattern, &g::mass_matrix_jacobian<mpreal>, p, d.sm.M, d,  \
                           values) < tolerance);                                                             \
      CHECK(jacobian_error(g::damping_matrix_jacobian_pattern, &g::damping_matrix_jacobian<mpreal>, p,       \
                           d.sm.C_total, d, values) < tolerance);                                                \
      CHECK(jacobian_error(g::gyroscopic_matrix_jacobian_pattern, &g::gyroscopic_matrix_jacobian<mpreal>, p, \
                           d.sm.G, d, values) < tolerance);                                                  \
      CHECK(jacobian_error(g::stiffness_matrix_jacobian_pattern, &g::stiffness_matrix_jacobian<mpreal>, p,   \
                           d.sm.K, d, values) < tolerance);                                                  \
      CHECK(jacobian_error(g::input_matrix_jacobian_pattern, &g::input_matrix_jacobian<mpreal>, p, d.sm.B,   \
                           d, values) < tolerance);                                                          \
      CHECK(jacobian_error(g::output_displacement_matrix_jacobian_pattern,                                   \
                           &g::output_displacement_matrix_jacobian<mpreal>, p, d.sm.Cd, d, values) < tolerance); \
      CHECK(jacobian_error(g::output_acceleration_matrix_jacobian_pattern,                                   \
                           &g::output_acceleration_matrix_jacobian<mpreal>, p, d.sm.Ca, d, values) < tolerance); \
    }                                                                                                        \
  } while (false)

}  // namespace

TEST_CASE("mdof2: generated code in 256-bit arithmetic equals the exact rationals", "[generated][mpreal]") {
  CHECK_GENERATED_AT_HIGH_PRECISION(mdof2, MBGEN_SOURCE_DIR "/examples/mdof2/mdof2.mdl");
}

TEST_CASE("spindle: generated code in 256-bit arithmetic equals the exact rationals", "[generated][mpreal]") {
  CHECK_GENERATED_AT_HIGH_PRECISION(spindle, MBGEN_SOURCE_DIR "/examples/spindle/spindle.mdl");
}

TEST_CASE("spinning spindle (gyroscopic terms): 256-bit generated code equals the exact rationals",
          "[generated][mpreal]") {
  CHECK_GENERATED_AT_HIGH_PRECISION(spindle_spin, MBGEN_SOURCE_DIR "/tests/generated_code/spindle_spin.mdl");
}
