// Transfer functions against a direct solve of P(s0) x = b at an exact complex point, and exact pole-zero
// cancellations.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "mbgen_test/files.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/test_support.hpp"
#include "symbolic/transfer_functions.hpp"

using namespace mbgen;
using namespace mbgen::symbolic;
using namespace mbgen::symbolic::test;

namespace {

GiNaC::ex evaluate_polynomial(const std::vector<GiNaC::ex>& c, const GiNaC::ex& s0) {
  GiNaC::ex v = 0;
  for (size_t k = c.size(); k-- > 0;) v = v * s0 + c[k];
  return v;
}

// y/u at s0 from the full (unreduced) equations: y = c(s0) P(s0)^-1 b, solved exactly.
GiNaC::ex direct(const SymbolicModel& sm, int o, int u, const GiNaC::ex& s0) {
  const GiNaC::exmap values = sm.values();
  const unsigned n = static_cast<unsigned>(sm.coordinates.size());
  GiNaC::matrix p(n, n), b(n, 1), x(n, 1);
  std::vector<GiNaC::symbol> unknowns;
  for (unsigned i = 0; i < n; ++i) {
    unknowns.emplace_back("x" + std::to_string(i));
    x(i, 0) = unknowns.back();
    b(i, 0) = sm.B(i, u).subs(values);
    for (unsigned j = 0; j < n; ++j)
      p(i, j) = (sm.M(i, j) * s0 * s0 + sm.C_total(i, j) * s0 + sm.K(i, j)).subs(values);
  }
  const GiNaC::matrix solution = p.solve(x, b);
  GiNaC::ex y = 0;
  for (unsigned i = 0; i < n; ++i)
    y += (sm.Cd(o, i) + sm.Cv(o, i) * s0 + sm.Ca(o, i) * s0 * s0).subs(values) * solution(i, 0);
  return y;
}

void check_against_direct_solve(const SymbolicModel& sm) {
  const GiNaC::ex s0 = GiNaC::numeric(3, 7) + GiNaC::numeric(1234, 5) * GiNaC::I;  // exact, complex
  const GiNaC::exmap values = sm.values();
  for (const TransferFunction& tf : sm.transfer_functions) {
    INFO(sm.model->outputs[tf.output].name << "/" << sm.model->inputs[tf.input].name);
    std::vector<GiNaC::ex> num, den;
    for (const GiNaC::ex& c : tf.numerator) num.push_back(c.subs(values));
    for (const GiNaC::ex& c : tf.denominator) den.push_back(c.subs(values));
    CHECK(den.back() == 1);
    const GiNaC::ex g = evaluate_polynomial(num, s0) / evaluate_polynomial(den, s0);
    CHECK(GiNaC::normal(GiNaC::expand(g - direct(sm, tf.output, tf.input, s0))).is_zero());
  }
}

std::string example_text(const std::string& name) { return mbgen::test::example_model_text(name); }

}  // namespace

TEST_CASE("transfer functions equal c P^-1 b at an exact complex frequency: mdof2") {
  const ir::ModelIr model = load_example("mdof2");
  check_against_direct_solve(derive(model));
}

TEST_CASE("transfer functions equal c P^-1 b at an exact complex frequency: spindle, with and without spin") {
  const ir::ModelIr model = load_example("spindle");
  check_against_direct_solve(derive(model));
  const ir::ModelIr spinning =
      frontend::parse_string(example_text("spindle") + "\nspin spindle about z speed n_sp\n"
                             "output ys displacement of spindle at (0, 0, 0.25) along y\n"
                             "output as acceleration of spindle at (0, 0, 0.25) along (1, 1, 0)\n"
                             "output vs velocity of housing along x\n", "spinning.mdl");
  DeriveOptions o;
  o.set["n_sp"] = "100";
  const SymbolicModel sm = derive(spinning, o);
  REQUIRE(sm.transfer_functions.size() == 6);
  check_against_direct_solve(sm);
  // Through the gyroscopic coupling a force along x now moves the spindle along y.
  CHECK_FALSE(sm.transfer_functions[3].numerator == std::vector<GiNaC::ex>{0});
}

TEST_CASE("transfer functions of a 3-coordinate block are symbolic, and a pair in another block is zero") {
  const ir::ModelIr model = frontend::parse_string(R"(model chain
param m = 1
param k = 100
param c = 0.5
ground g
body b1 {
  mass m
  dof x y
}
body b2 {
  mass 2*m
  dof x
}
spring s1 {
  from g
  to b1
  along x
  stiffness k
  damping c
}
spring s2 {
  from b1
  to b2
  along x
  stiffness k
}
spring s3 {
  from g
  to b1
  along y
  stiffness 3*k
}
input F force on b1 along x
output y1 velocity of b1 along y
output x2 acceleration of b2 along x
)", "chain.mdl");
  const SymbolicModel sm = derive(model);
  REQUIRE(sm.blocks.size() == 2);
  const TransferFunction& zero = sm.transfer_functions[0];
  CHECK(zero.coordinates.empty());
  CHECK(zero.numerator == std::vector<GiNaC::ex>{0});
  CHECK(zero.denominator == std::vector<GiNaC::ex>{1});
  const TransferFunction& x2 = sm.transfer_functions[1];
  CHECK(x2.symbolic);
  CHECK(x2.coordinates == std::vector<int>{0, 2});
  // Hand-derived: P = [[m s^2 + c s + 2k, -k], [-k, 2m s^2 + k]], x2/F = k/det P, acceleration multiplies by s^2;
  // det P = 2m^2 s^4 + 2mc s^3 + 5mk s^2 + ck s + k^2.
  const GiNaC::ex m = symbol_of(sm, "m"), k = symbol_of(sm, "k"), c = symbol_of(sm, "c");
  const GiNaC::ex lead = 2 * m * m;
  const std::vector<GiNaC::ex> den = {k * k / lead, c * k / lead, 5 * m * k / lead, 2 * m * c / lead, 1};
  REQUIRE(x2.denominator.size() == 5);
  for (size_t i = 0; i < 5; ++i) CHECK(same(x2.denominator[i], den[i]));
  REQUIRE(x2.numerator.size() == 3);
  CHECK(same(x2.numerator[0], 0));
  CHECK(same(x2.numerator[1], 0));
  CHECK(same(x2.numerator[2], k / lead));
  check_against_direct_solve(sm);
  CHECK(sm.cancellations.empty());
}

TEST_CASE("an input/output pair that does not see the antisymmetric mode reports the cancellation") {
  // Three equal masses in a symmetric chain between two walls. The mode (1, 0, -1) at sqrt(2k/m) leaves the middle
  // mass still, so the middle mass's own transfer function does not show it: m s^2 + 2k divides numerator and
  // denominator.
  const ir::ModelIr model = frontend::parse_string(R"(model sym3
param m = 2
param k = 800
ground g
body b1 {
  mass m
  dof x
}
body b2 {
  mass m
  dof x
}
body b3 {
  mass m
  dof x
}
spring s1 {
  from g
  to b1
  along x
  stiffness k
}
spring s2 {
  from b1
  to b2
  along x
  stiffness k
}
spring s3 {
  from b2
  to b3
  along x
  stiffness k
}
spring s4 {
  from b3
  to g
  along x
  stiffness k
}
input F2 force on b2 along x
input F1 force on b1 along x
output x2 displacement of b2 along x
)", "sym3.mdl");
  const SymbolicModel sm = derive(model);
  REQUIRE(sm.transfer_functions.size() == 2);
  check_against_direct_solve(sm);
  // The reported TF keeps the common factor (numerator and denominator as derived).
  CHECK(sm.transfer_functions[0].denominator.size() == 7);
  // Both pairs miss the mode: F2 does not excite it, x2 does not observe it.
  REQUIRE(sm.cancellations.size() == 2);
  const GiNaC::symbol s = sm.s;
  for (int u = 0; u < 2; ++u) {
    const Cancellation& c = sm.cancellations[u];
    CHECK(c.output == 0);
    CHECK(c.input == u);
    CHECK(same(c.common_factor, s * s + 800));  // s^2 + 2k/m, monic
  }
  // sqrt(800)/(2 pi) = 4.50158 Hz
  CHECK(sm.cancellations[0].text ==
        "x2/F2: numerator and denominator share the factor (800+s^2) at the current parameter values, so the poles "
        "4.50158 Hz (zeta 0) cancel and do not show in this transfer function");
  // With the middle spring stiffer on one side the chain is no longer symmetric: no cancellation.
  DeriveOptions o;
  o.set["k"] = "800";
  ir::ModelIr lopsided = model;
  lopsided.elements[3].stiffness[0] = ir::Expr::number("801");
  CHECK(derive(lopsided, o).cancellations.empty());
}

namespace {

// n equal masses in a row between two walls, force and displacement at the middle one (n odd): the antisymmetric
// modes leave it still, so (n - 1) / 2 pole pairs cancel.
std::string symmetric_row(int n) {
  std::string t = "model row\nparam m = 2\nparam k = 800\nparam c = 0.5\nground g\n";
  for (int i = 1; i <= n; ++i) t += "body b" + std::to_string(i) + " {\n  mass m\n  dof x\n}\n";
  for (int i = 0; i <= n; ++i)
    t += "spring s" + std::to_string(i) + " {\n  from " + (i == 0 ? std::string("g") : "b" + std::to_string(i)) +
         "\n  to " + (i == n ? std::string("g") : "b" + std::to_string(i + 1)) +
         "\n  along x\n  stiffness k\n  damping c\n}\n";
  const std::string mid = "b" + std::to_string((n + 1) / 2);
  return t + "input F force on " + mid + " along x\noutput x displacement of " + mid + " along x\n";
}

}  // namespace

TEST_CASE("exact cancellations on a 41-coordinate block (multimodular determinants, exact gcd)") {
  const ir::ModelIr model = frontend::parse_string(symmetric_row(41), "row41.mdl");
  const SymbolicModel sm = derive(model);
  REQUIRE(sm.transfer_functions.size() == 1);
  const TransferFunction& tf = sm.transfer_functions[0];
  CHECK(tf.exact);
  CHECK(tf.denominator.size() == 83);
  check_against_direct_solve(sm);
  REQUIRE(sm.cancellations.size() == 1);
  CHECK(sm.cancellations[0].common_factor.degree(sm.s) == 40);  // 20 antisymmetric pole pairs
}

TEST_CASE("a block over the exact-coefficient limit: no coefficients, cancellations found modulo primes") {
  const int n = kMaxExactBlockSize + 1;
  const SymbolicModel sm = derive(frontend::parse_string(symmetric_row(n), "row.mdl"));
  REQUIRE(sm.transfer_functions.size() == 1);
  const TransferFunction& tf = sm.transfer_functions[0];
  CHECK_FALSE(tf.exact);
  CHECK_FALSE(tf.symbolic);
  CHECK(tf.numerator.empty());
  CHECK(tf.denominator.empty());
  CHECK(static_cast<int>(tf.coordinates.size()) == n);
  REQUIRE(sm.cancellations.size() == 1);
  CHECK(sm.cancellations[0].common_factor.is_zero());
  CHECK(sm.cancellations[0].text ==
        "x/F: numerator and denominator probably share a factor of degree " + std::to_string(n - 1) +
            " at the current parameter values (they do modulo two primes; the block of " + std::to_string(n) +
            " coordinates is too large for exact coefficients), so " + std::to_string(n - 1) +
            " poles probably cancel and do not show in this transfer function");
  // Off-centre, the input sees every mode: no cancellation, proven modulo a prime.
  ir::ModelIr lopsided = frontend::parse_string(symmetric_row(n), "row.mdl");
  lopsided.elements[0].stiffness[0] = ir::Expr::number("801");
  CHECK(derive(lopsided).cancellations.empty());
}
