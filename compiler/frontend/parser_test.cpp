#include "mbgen_test/files.hpp"
#include "frontend/parser.hpp"

#include <catch2/catch.hpp>

#include "frontend/diagnostics.hpp"

using namespace mbgen;

namespace {

std::string error_of(const std::string& text) {
  try {
    frontend::parse_string(text, "t.mdl");
  } catch (const frontend::ModelError& e) {
    return e.what();
  }
  return "no error";
}

const char* const kMinimal = R"(model two
param m = 2 "kg" estimate in [0, inf]
param k = 1e3
ground g
body b { mass m; dof x }
spring s { from g; to b; along x; stiffness k }
)";

}  // namespace

TEST_CASE("the example models parse", "[parser]") {
  const ir::ModelIr mdof2 = frontend::parse_file(mbgen::test::example_model_path("mdof2"));
  CHECK(mdof2.name == "mdof2");
  CHECK(mdof2.parameters.size() == 8);
  CHECK(mdof2.bodies.size() == 2);
  CHECK(mdof2.elements.size() == 3);
  CHECK(mdof2.find_parameter("c12")->role == ir::Role::Fixed);
  CHECK(mdof2.find_parameter("k11")->role == ir::Role::Estimate);
  CHECK(mdof2.find_parameter("k11")->unit == "N/m");
  CHECK(ir::to_string(*mdof2.find_parameter("k11")->upper) == "1e9");

  const ir::ModelIr spindle = frontend::parse_file(mbgen::test::example_model_path("spindle"));
  CHECK(spindle.bodies.size() == 2);
  CHECK(spindle.elements.size() == 9);
  CHECK(spindle.find_body("spindle")->dofs.size() == 5);
  const ir::Parameter* j = spindle.find_parameter("J_sxx");
  REQUIRE(j);
  CHECK(j->derived);
  CHECK(ir::to_string(j->value) == "m_s*(3*(R_so^2 + R_si^2) + L_s^2)/12");
  CHECK_FALSE(spindle.find_parameter("m_s")->derived);
  CHECK(spindle.outputs.size() == 3);
  CHECK(ir::to_string(spindle.outputs[1].at.point[2]) == "-0.250");
}

TEST_CASE("implicit points are the centre of mass or the ground origin", "[parser]") {
  const ir::ModelIr m = frontend::parse_string(
      "ground g\nbody b { mass 1; at (1, 2, 3); dof x }\nspring s { from g; to b; along x; stiffness 1 }\n", "t.mdl");
  CHECK(m.name == "t");
  const ir::Element& s = m.elements[0];
  CHECK(ir::to_string(s.a.point[0]) == "0");
  CHECK(ir::to_string(s.b.point[2]) == "3");
  CHECK_FALSE(s.b.has_point);
}

TEST_CASE("expressions print with the fewest parentheses and re-parse to the same text", "[parser]") {
  for (const char* text : {"a - (b - c)", "a - b - c", "a/(b*c)", "-a^2", "(-a)^2", "a^b^c", "(a^b)^c", "a*-b",
                           "sqrt(a + b)/2", "2*pi*n", "-(-a)", "(a + b)*(c - d)/e", "a - b + c - d",
                           "(a + b) + c", "a*(b*c)", "a*b/c*d", "a*(b/c)", "-a*b - c"}) {
    const std::string model = std::string("param a = 1\nparam b = 2\nparam c = 3\nparam d = 4\nparam e = 5\n"
                                          "param n = 6\nparam r = ") + text + "\n";
    const ir::ModelIr m = frontend::parse_string(model, "t.mdl");
    CHECK(ir::to_string(m.find_parameter("r")->value) == text);
  }
  // A sum is one node whose subtracted terms are negations: `a + -b` and `a - b` are the same tree.
  const ir::ModelIr m = frontend::parse_string("param a = 1\nparam b = 2\nparam r = a + -b\n", "t.mdl");
  CHECK(ir::to_string(m.find_parameter("r")->value) == "a - b");
}

TEST_CASE("statements continue across lines inside brackets and after operators", "[parser]") {
  const ir::ModelIr m = frontend::parse_string(
      "param a = 1 +\n  2\nparam b = (a\n  * 3)\nparam c = 4 \"m\" known in [0,\n 10]\n", "t.mdl");
  CHECK(ir::to_string(m.find_parameter("a")->value) == "1 + 2");
  CHECK(ir::to_string(m.find_parameter("b")->value) == "a*3");
  CHECK(ir::to_string(*m.find_parameter("c")->upper) == "10");
}

TEST_CASE("a minimal model parses", "[parser]") {
  const ir::ModelIr m = frontend::parse_string(kMinimal, "t.mdl");
  CHECK(m.find_parameter("m")->role == ir::Role::Estimate);
  CHECK(ir::to_string(*m.find_parameter("m")->lower) == "0");
  CHECK_FALSE(m.find_parameter("m")->upper.has_value());
}

TEST_CASE("syntax errors name line, column and what was expected", "[parser][errors]") {
  CHECK(error_of("param = 3\n") == "t.mdl:1:7: error: expected a parameter name, found `=`");
  CHECK(error_of("param a = 3 *\n\n") == "t.mdl:3:1: error: expected an expression (a number, a parameter name or `(`), found end of file");
  CHECK(error_of("bogus x\n") ==
        "t.mdl:1:1: error: expected a statement (model, param, ground, body, spring, spring3, torsion, spin, input, output, filter), found `bogus`");
  CHECK(error_of("param a = 1 $\n") == "t.mdl:1:13: error: unexpected character `$`");
  CHECK(error_of("param a = \"kg\n") == "t.mdl:1:11: error: unterminated string: expected a closing `\"` on the same line");
  CHECK(error_of("ground g\nbody b { mass 1\n dof q }\n") ==
        "t.mdl:3:6: error: expected a coordinate (x, y, z, rx, ry, rz), found `q`");
  CHECK(error_of("ground g\nbody b { mass 1; dof x\n") == "t.mdl:3:1: error: expected `}` to close the block, found end of file");
  CHECK(error_of("param a = 2x\n") == "t.mdl:1:11: error: malformed number `2x`: a number must not run into a name");
  CHECK(error_of("param a = tan(1)\n") == "t.mdl:1:11: error: unknown function `tan`: the functions are sqrt, sin and cos");
}

TEST_CASE("semantic errors name the offending declaration", "[parser][errors]") {
  CHECK(error_of("param a = b\n") == "t.mdl:1:11: error: unknown parameter `b`: declare it with `param b = VALUE`");
  CHECK(error_of("param a = b\nparam b = a\n") == "t.mdl:1:7: error: parameter `a` is defined in terms of itself");
  CHECK(error_of("param a = 1\nparam a = 2\n") ==
        "t.mdl:2:7: error: `a` is already declared at line 1, column 7 (as a parameter); each name is declared once");
  CHECK(error_of("param a = 1\nparam b = a estimate\n") ==
        "t.mdl:2:13: error: parameter `b` is derived (an expression of other parameters) and cannot be `estimate`; estimate the parameters it is built from");
  CHECK(error_of("ground g\nbody b { mass 1; dof x }\n") ==
        "t.mdl:2:6: error: body `b` is not connected: no spring, spring3 or torsion element attaches to it");
  CHECK(error_of("ground g\nbody b { mass 1; dof x }\nspring s { from g; to c; along x; stiffness 1 }\n") ==
        "t.mdl:3:23: error: unknown frame `c`: expected the name of a body or a ground");
  CHECK(error_of("ground g\nbody b { mass 1; dof x }\nspring s { from b; to b; along x; stiffness 1 }\n") ==
        "t.mdl:3:23: error: element `s` joins `b` to itself");
  CHECK(error_of("ground g\nbody b { mass 1; dof x }\nspring3 s { from g; to b; stiffness 1 }\n") ==
        "t.mdl:3:27: error: a spring3 takes 3 values (x, y, z) for `stiffness`, found 1");
  CHECK(error_of("ground g\nbody b { mass 1 }\n") ==
        "t.mdl:2:6: error: body `b` has no coordinates: give it a `dof` line (x y z rx ry rz)");
  CHECK(error_of("ground g\nbody b { mass 1; dof x }\nspring s { from g; to b; along x; stiffness 1 }\n"
                 "output y displacement of g along x\n") ==
        "t.mdl:4:26: error: output `y` is on ground `g`, which does not move: put it on a body");
  CHECK(error_of("ground g\nbody b { mass 1; dof x }\nspring s { from g; to b; along (0, 0, 0); stiffness 1 }\n") ==
        "t.mdl:3:32: error: a direction must not be the zero vector");
  CHECK(error_of("ground g\nbody b { mass 1; dof x }\nspring s { from g; to b; stiffness 1 }\n") ==
        "t.mdl:3:8: error: spring `s` has no `along` direction");
}
