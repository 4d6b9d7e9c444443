// Output filters: each filtered transfer function equals the unfiltered one times the filter's own transfer
// function, exactly (written out here from the definitions in docs/language.md, not from output_filters.cpp).
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "mbgen_test/files.hpp"
#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/test_support.hpp"

using namespace mbgen;
using namespace mbgen::symbolic;
using namespace mbgen::symbolic::test;

namespace {

std::string mdof2_text() { return mbgen::test::example_model_text("mdof2"); }

GiNaC::ex ratio(const TransferFunction& tf, const GiNaC::symbol& s) {
  GiNaC::ex num = 0, den = 0;
  for (std::size_t k = 0; k < tf.numerator.size(); ++k) num += tf.numerator[k] * GiNaC::pow(s, static_cast<int>(k));
  for (std::size_t k = 0; k < tf.denominator.size(); ++k)
    den += tf.denominator[k] * GiNaC::pow(s, static_cast<int>(k));
  return num / den;
}

const TransferFunction& tf_of(const SymbolicModel& sm, const std::string& output) {
  for (const TransferFunction& tf : sm.transfer_functions)
    if (sm.model->outputs[tf.output].name == output) return tf;
  throw std::runtime_error("no transfer function of " + output);
}

// The filtered model's G(s) for `output`, and the unfiltered one's, both over the parameter symbols (the
// filtered model's symbols, substituted into the plain one's by name).
struct Pair {
  GiNaC::ex filtered, plain;
  SymbolicModel sm;
};

GiNaC::ex rename_symbols(const GiNaC::ex& e, const SymbolicModel& from, const SymbolicModel& to) {
  GiNaC::exmap map;
  for (const FreeParameter& p : from.parameters) {
    const int i = to.parameter_index(p.name);
    if (i >= 0) map[p.sym] = to.parameters[static_cast<std::size_t>(i)].sym;
  }
  map[from.s] = to.s;
  return e.subs(map);
}

// Two transfer functions agree: exactly where both are symbolic; where a block is too large for symbolic
// coefficients (more than three coordinates: filter states count), the derived one holds exact numbers at the
// parameters' values, and both are compared at those values on the imaginary axis to 1e-12.
bool agree(const SymbolicModel& sm, const TransferFunction& tf, const GiNaC::ex& expected) {
  const GiNaC::ex derived = ratio(tf, sm.s);
  if (tf.symbolic) return same(derived, expected);
  const GiNaC::exmap values = sm.values();
  for (double f : {3.0, 47.0, 90.0, 166.0, 400.0, 1500.0}) {
    GiNaC::exmap at = values;
    at[sm.s] = GiNaC::I * 2 * GiNaC::Pi * GiNaC::numeric(f);
    const GiNaC::ex a = GiNaC::evalf(derived.subs(at)), b = GiNaC::evalf(expected.subs(at));
    const double diff = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(GiNaC::abs(a - b))).to_double();
    const double size = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(GiNaC::abs(b))).to_double();
    if (!(diff <= 1e-12 * size)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("output filters: each kind multiplies the output's transfer function by its own, exactly") {
  const std::string filters[] = {
      "param fc = 450 \"Hz\" estimate in [1, 1e5]\nparam zf = 0.7 \"\" estimate in [0, 2]\n"
      "filter lp on d2 lowpass2 cutoff fc damping zf\n",
      "param fc = 4 \"Hz\" estimate in [0.01, 1e3]\nfilter hp on d2 highpass1 cutoff fc\n",
      "param fc = 30 \"Hz\" estimate in [0.01, 1e3]\nparam zf = 0.5 \"\" estimate in [0, 2]\n"
      "filter hp2 on d2 highpass2 cutoff fc damping zf\n",
      "param tau = 5e-4 \"s\" estimate in [0, 0.01]\nfilter dl on d2 delay time tau sections 3\n",
  };
  const ir::ModelIr plain_model = frontend::parse_string(mdof2_text(), "mdof2.mdl");
  const SymbolicModel plain = derive(plain_model);
  for (int kind = 0; kind < 4; ++kind) {
    const ir::ModelIr model = frontend::parse_string(mdof2_text() + filters[kind], "filtered.mdl");
    const SymbolicModel sm = derive(model);
    INFO(filters[kind]);
    const GiNaC::ex s = sm.s;
    const GiNaC::ex fc = kind < 3 ? symbol_of(sm, "fc") : GiNaC::ex(0);
    const GiNaC::ex wc = 2 * GiNaC::Pi * fc;
    GiNaC::ex T;
    if (kind == 0) {
      const GiNaC::ex z = symbol_of(sm, "zf");
      T = wc * wc / (s * s + 2 * z * wc * s + wc * wc);
    } else if (kind == 1) {
      T = s / (s + wc);
    } else if (kind == 2) {
      const GiNaC::ex z = symbol_of(sm, "zf");
      T = s * s / (s * s + 2 * z * wc * s + wc * wc);
    } else {
      const GiNaC::ex t = symbol_of(sm, "tau") / 3;  // three Pade (2,2) sections of tau/3
      T = GiNaC::pow((1 - s * t / 2 + s * s * t * t / 12) / (1 + s * t / 2 + s * s * t * t / 12), 3);
    }
    const GiNaC::ex expected = rename_symbols(ratio(tf_of(plain, "d2"), plain.s), plain, sm) * T;
    CHECK(agree(sm, tf_of(sm, "d2"), expected));
    // The other output is untouched.
    CHECK(agree(sm, tf_of(sm, "d1"), rename_symbols(ratio(tf_of(plain, "d1"), plain.s), plain, sm)));
    // The filter's states are named coordinates after the bodies'.
    REQUIRE(sm.coordinates.size() == (kind == 3 ? 5u : 3u));
    CHECK(sm.coordinates[0].name() == "mass1.x");
    CHECK(sm.coordinates[2].is_filter_state());
  }
}

TEST_CASE("output filters: a gain multiplies the output by its factor, with no state, and may not be zero") {
  const ir::ModelIr plain_model = frontend::parse_string(mdof2_text(), "mdof2.mdl");
  const SymbolicModel plain = derive(plain_model);
  const std::string gain = "param g = -4/5 \"\" estimate in [-10, 10]\nfilter cal on d2 gain factor g\n";
  const ir::ModelIr model = frontend::parse_string(mdof2_text() + gain, "gain.mdl");  // sm points into it
  const SymbolicModel sm = derive(model);
  const GiNaC::ex expected = rename_symbols(ratio(tf_of(plain, "d2"), plain.s), plain, sm) * symbol_of(sm, "g");
  CHECK(agree(sm, tf_of(sm, "d2"), expected));
  CHECK(agree(sm, tf_of(sm, "d1"), rename_symbols(ratio(tf_of(plain, "d1"), plain.s), plain, sm)));
  CHECK(sm.coordinates.size() == 2u);  // no filter state
  // A gain that is zero at the parameters' values would make the output read nothing.
  const std::string zero = "param g = 0 \"\" estimate in [-10, 10]\nfilter cal on d2 gain factor g\n";
  CHECK_THROWS_WITH(derive(frontend::parse_string(mdof2_text() + zero, "zero.mdl")),
                    Catch::Contains("its gain factor is 0 at the parameters' values"));
}

TEST_CASE("output filters: filters on one output apply in declaration order, also on an acceleration output") {
  const std::string text = mdof2_text() +
                           "param fa = 300 \"Hz\"\nparam fb = 5 \"Hz\"\n"
                           "output a1 acceleration of mass1 along x\n"
                           "filter first on a1 lowpass2 cutoff fa damping 0.5\n"
                           "filter second on a1 highpass1 cutoff fb\n";
  const ir::ModelIr model = frontend::parse_string(text, "chain.mdl");
  const SymbolicModel sm = derive(model);
  const ir::ModelIr plain_model = frontend::parse_string(mdof2_text() + "output a1 acceleration of mass1 along x\n", "a.mdl");
  const SymbolicModel plain = derive(plain_model);
  const GiNaC::ex s = sm.s;
  const GiNaC::ex wa = 2 * GiNaC::Pi * 300, wb = 2 * GiNaC::Pi * 5;
  const GiNaC::ex T = wa * wa / (s * s + wa * s + wa * wa) * s / (s + wb);
  CHECK(agree(sm, tf_of(sm, "a1"), rename_symbols(ratio(tf_of(plain, "a1"), plain.s), plain, sm) * T));
}

TEST_CASE("output filters: malformed filter statements are rejected with their location") {
  const auto fails_with = [](const std::string& filter, const std::string& message) {
    try {
      frontend::parse_string(mdof2_text() + filter, "bad.mdl");
      FAIL("accepted: " << filter);
    } catch (const frontend::ModelError& e) {
      CHECK_THAT(e.what(), Catch::Contains(message));
      CHECK_THAT(e.what(), Catch::Contains("bad.mdl:"));
    }
  };
  fails_with("filter f on nowhere lowpass2 cutoff 100 damping 0.7\n", "not an output");
  fails_with("filter f on F1 highpass1 cutoff 100\n", "not an output");
  fails_with("filter f on d1 lowpass2 cutoff 100\n", "has no `damping`");
  fails_with("filter f on d1 delay sections 2\n", "has no `time`");
  fails_with("filter f on d1 delay time 1e-3 sections 0\n", "sections from 1 to 16");
  fails_with("filter f on d1 highpass1 cutoff 5 damping 0.5\n", "highpass1 filter item");
  fails_with("filter f on d1 bandpass cutoff 5\n", "a filter kind");
  fails_with("filter beam1 on d1 highpass1 cutoff 5\n", "already declared");
  fails_with("filter f on d1 highpass1 cutoff q\n", "unknown parameter `q`");
}
