// ir::Expr -> GiNaC: exact decimal literals, constants, functions, derived parameters, --set overrides.
#include <catch2/catch.hpp>

#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/to_ginac.hpp"

using namespace mbgen;
using namespace mbgen::symbolic;

namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const frontend::ModelError& e) {
    return e.what();
  }
  return "no error";
}

const ir::ModelIr two_params = frontend::parse_string(
    "model p\n"
    "param a = 0.127\n"
    "param b = a*2 + 1\n"
    "param c = b^2/a\n", "p.mdl");

}  // namespace

TEST_CASE("decimal literals are exact rationals") {
  CHECK(parse_decimal("0.127") == GiNaC::numeric(127, 1000));
  CHECK(parse_decimal("60e6") == GiNaC::numeric(60000000));
  CHECK(parse_decimal("1.5E-3") == GiNaC::numeric(3, 2000));
  CHECK(parse_decimal("0.04e6") == GiNaC::numeric(40000));
  CHECK(parse_decimal("3") == GiNaC::numeric(3));
  CHECK(parse_decimal("-2.50") == GiNaC::numeric(-5, 2));
  CHECK(parse_decimal(".5") == GiNaC::numeric(1, 2));
  CHECK(parse_decimal("5.") == GiNaC::numeric(5));
  CHECK(parse_decimal("1e+2") == GiNaC::numeric(100));
  // More digits than a double holds, still exact.
  CHECK(parse_decimal("0.1000000000000000000000000000001") ==
        GiNaC::numeric(1, 10) + GiNaC::pow(GiNaC::numeric(10), -31));
  CHECK(parse_decimal("0.1").is_rational());
  for (const char* bad : {"", "e5", "1e", "1.2.3", "0x10", "1e5.0", "--1", "inf", "nan", "1 "}) {
    INFO(bad);
    CHECK_FALSE(is_decimal_literal(bad));
    CHECK_THROWS_AS(parse_decimal(bad), std::invalid_argument);
  }
}

TEST_CASE("expressions: pi, functions and derived parameters substituted recursively") {
  const ParameterTable t(two_params);
  REQUIRE(t.free_parameters().size() == 1);
  const GiNaC::ex a = t.free_parameters()[0].sym;
  CHECK(t.free_parameters()[0].value == GiNaC::numeric(127, 1000));
  const ir::SourceLoc l{};
  using K = ir::Expr::Kind;
  const ir::Expr c = ir::Expr::symbol("c", l);
  CHECK(GiNaC::normal(t.convert(c) - GiNaC::pow(2 * a + 1, 2) / a).is_zero());
  const ir::Expr pi_over_4 = ir::Expr::binary(K::Div, ir::Expr::symbol("pi"), ir::Expr::number("4"));
  CHECK(t.convert(ir::Expr::call("sin", {pi_over_4})) == GiNaC::sqrt(GiNaC::ex(2)) / 2);
  CHECK(t.convert(ir::Expr::call("cos", {ir::Expr::symbol("pi")})) == -1);
  CHECK(t.convert(ir::Expr::call("sqrt", {ir::Expr::number("4")})) == 2);
  CHECK(t.convert(ir::Expr::negate(ir::Expr::binary(K::Pow, ir::Expr::number("2"), ir::Expr::number("3")))) == -8);
  CHECK(t.convert(ir::Expr::binary(K::Sub, ir::Expr::number("1"), ir::Expr::number("0.25"))) ==
        GiNaC::numeric(3, 4));
  // No floating point anywhere: b = 2a + 1 = 1.254, c = b^2/a exactly.
  const GiNaC::ex c_value = t.convert(c).subs(t.values());
  CHECK(c_value.info(GiNaC::info_flags::rational));
  CHECK(c_value == GiNaC::pow(GiNaC::numeric(1254, 1000), 2) / GiNaC::numeric(127, 1000));
}

TEST_CASE("a --set override replaces a free parameter's value exactly") {
  const ParameterTable t(two_params, {{"a", "1.5E-3"}});
  CHECK(t.free_parameters()[0].value == GiNaC::numeric(3, 2000));
  DeriveOptions o;
  o.set["a"] = "-2";
  CHECK(ParameterTable(two_params, o.set).free_parameters()[0].value == -2);
}

TEST_CASE("bad --set values and names are rejected with a clear message") {
  CHECK(error_of([] { ParameterTable(two_params, {{"zz", "1"}}); }) ==
        "p.mdl: error: --set zz=1: the model has no parameter named `zz`; only declared parameters can be set");
  CHECK(error_of([] { ParameterTable(two_params, {{"b", "1"}}); }) ==
        "p.mdl:3:7: error: --set b=1: `b` is derived (= a*2 + 1) and cannot be set; set the free parameters it "
        "is built from instead");
  CHECK(error_of([] { ParameterTable(two_params, {{"a", "1,5"}}); }) ==
        "p.mdl: error: --set a=1,5: the value must be a decimal number such as 1.5, -2 or 60e6");
  CHECK(error_of([] { ParameterTable(two_params, {{"a", ""}}); }).find("the value must be a decimal number") !=
        std::string::npos);
}

TEST_CASE("a derived-parameter cycle and an unknown name are located at the IR node") {
  // The parser rejects both already; the symbolic stage must not rely on it (models also come from extension
  // operators), so the IR is edited by hand here.
  ir::ModelIr cyclic = two_params;
  cyclic.parameters[1].value = ir::Expr::binary(ir::Expr::Kind::Mul, ir::Expr::symbol("c", {3, 11}),
                                                ir::Expr::number("2", {3, 13}), {3, 12});
  // The table evaluates every parameter when it is made (their values must be real), in declaration order: the
  // cycle is met at b.
  CHECK(error_of([&] { ParameterTable(cyclic).convert(ir::Expr::symbol("c")); }) ==
        "p.mdl:3:7: error: parameter `b` is defined in terms of itself (b -> c -> b); give one of these "
        "parameters a numeric value");
  ir::ModelIr unknown = two_params;
  unknown.parameters[2].value = ir::Expr::symbol("nope", {4, 11});
  CHECK(error_of([&] { ParameterTable(unknown).convert(ir::Expr::symbol("c")); }) ==
        "p.mdl:4:11: error: unknown parameter `nope`: declare it with `param nope = VALUE`");
  ir::ModelIr bad_function = two_params;
  bad_function.parameters[2].value = ir::Expr::call("tan", {ir::Expr::symbol("a")}, {4, 11});
  CHECK(error_of([&] { ParameterTable(bad_function).convert(ir::Expr::symbol("c")); }) ==
        "p.mdl:4:11: error: unknown function `tan`; the functions are sqrt, sin and cos");
}

TEST_CASE("an expression without a value at the parameters' values is refused where it is written") {
  // GiNaC throws from inside its substitution here (and leaks what it was building), so the table must find these
  // before it substitutes: each is a model error at the node that has no value.
  auto error_for = [](const std::string& value) {
    return error_of([&] { ParameterTable(frontend::parse_string("model z\nparam q = 0\nparam t = " + value + "\n",
                                                                "z.mdl")); });
  };
  const std::string no_value = " has no value at the parameters' values: ";
  CHECK(error_for("1/sqrt(q)") == "z.mdl:3:12: error: `1/sqrt(q)`" + no_value + "division by zero");
  CHECK(error_for("0^q") == "z.mdl:3:12: error: `0^q`" + no_value + "0^0 is undefined");
  CHECK(error_for("sin(2/(q*q))") == "z.mdl:3:16: error: `2/(q*q)`" + no_value + "division by zero");
  CHECK(error_for("q^(0-2)") == "z.mdl:3:12: error: `q^(0 - 2)`" + no_value + "division by zero");
  // With a value, the same expressions are fine.
  CHECK(error_of([] {
          ParameterTable(frontend::parse_string("model z\nparam q = 4\nparam t = 1/sqrt(q) + 0^q\n", "z.mdl"));
        }) == "no error");
}
