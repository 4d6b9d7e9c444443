// An input's gain (docs/language.md, `input ... gain EXPR`): the record reads EXPR times the applied force, so the
// input's column of B, and every transfer function from that input, is the ungained one divided by EXPR; the other
// inputs' columns are untouched. Expected values are the same model derived without the gain, divided here.
#include <catch2/catch.hpp>

#include <algorithm>

#include "mbgen_test/files.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/test_support.hpp"

using namespace mbgen;
using namespace mbgen::symbolic;
using namespace mbgen::symbolic::test;

namespace {

// mdof2 with a second force on mass2; `gain` is appended to that input's statement.
std::string two_inputs(const std::string& gain) {
  return mbgen::test::example_model_text("mdof2") + "input F2 force on mass2 along x" + gain + "\n";
}

GiNaC::ex ratio(const TransferFunction& tf, const GiNaC::symbol& s) {
  GiNaC::ex num = 0, den = 0;
  for (std::size_t k = 0; k < tf.numerator.size(); ++k) num += tf.numerator[k] * GiNaC::pow(s, static_cast<int>(k));
  for (std::size_t k = 0; k < tf.denominator.size(); ++k)
    den += tf.denominator[k] * GiNaC::pow(s, static_cast<int>(k));
  return num / den;
}

GiNaC::ex tf_ratio(const SymbolicModel& sm, const std::string& output, const std::string& input) {
  for (const TransferFunction& tf : sm.transfer_functions)
    if (sm.model->outputs[tf.output].name == output && sm.model->inputs[tf.input].name == input)
      return ratio(tf, sm.s);
  throw std::runtime_error("no transfer function " + output + "/" + input);
}

}  // namespace

TEST_CASE("input gain: the input's column of B and its transfer functions are divided by the gain") {
  const ir::ModelIr plain_model = frontend::parse_string(two_inputs(""), "plain.mdl");
  const SymbolicModel plain = derive(plain_model);
  const ir::ModelIr model = frontend::parse_string(
      "param g = 4/5 \"\" estimate in [0, 10]\n" + two_inputs(" gain 2*g"), "gain.mdl");  // sm points into it
  const SymbolicModel sm = derive(model);
  REQUIRE(sm.B.cols() == 2u);
  GiNaC::exmap map = rename_symbols(plain, sm);
  map[plain.s] = sm.s;
  const GiNaC::ex g = symbol_of(sm, "g");
  for (unsigned i = 0; i < sm.B.rows(); ++i) {
    CHECK(same(sm.B(i, 0), plain.B(i, 0).subs(map)));
    CHECK(same(sm.B(i, 1), plain.B(i, 1).subs(map) / (2 * g)));
  }
  CHECK(same(sm.B(1, 1).diff(GiNaC::ex_to<GiNaC::symbol>(g)), -plain.B(1, 1).subs(map) / (2 * g * g)));
  for (const char* output : {"d1", "d2"}) {
    INFO(output);
    CHECK(same(tf_ratio(sm, output, "F1"), tf_ratio(plain, output, "F1").subs(map)));
    CHECK(same(tf_ratio(sm, output, "F2"), tf_ratio(plain, output, "F2").subs(map) / (2 * g)));
  }
  // The other matrices do not change.
  CHECK(same(sm.K, substituted(plain.K, map)));
  CHECK(same(sm.Cd, substituted(plain.Cd, map)));
}

TEST_CASE("input gain: a gain of zero is rejected, as written or at the parameters' values") {
  const auto error_of = [](const std::string& text) -> std::string {
    try {
      const ir::ModelIr model = frontend::parse_string(text, "t.mdl");
      derive(model);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string text = mbgen::test::example_model_text("mdof2");
  const std::size_t lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  const std::string line = std::to_string(lines + 1);
  CHECK(error_of(two_inputs(" gain 0")) ==
        "t.mdl:" + line + ":38: error: input `F2`: its gain is 0: its record would read no force (a gain is what the "
                          "record reads per unit of the applied force, e.g. 0.98, or -1 for a reversed sign)");
  CHECK(error_of(two_inputs(" gain -0.0*k11")).find("t.mdl:" + line + ":38: error: input `F2`: its gain is 0") == 0);
  CHECK(error_of(two_inputs(" gain")) ==
        "t.mdl:" + line + ":37: error: expected an expression (a number, a parameter name or `(`), found end of line");
  CHECK(error_of(two_inputs(" gain h")).find("unknown parameter `h`") != std::string::npos);
  CHECK_THAT(error_of("param h = 0\n" + two_inputs(" gain h")),
             Catch::Contains("input `F2`: its gain is 0 at the parameters' values"));
}
