#include "mbgen_test/files.hpp"
#include "frontend/model_writer.hpp"

#include <catch2/catch.hpp>

#include "frontend/parser.hpp"

using namespace mbgen;

namespace {

std::string text(const ir::Expr& e) { return ir::to_string(e); }
std::string text(const std::optional<ir::Expr>& e) { return e ? ir::to_string(*e) : "<none>"; }

// Field-by-field comparison of two models, independent of the writer (locations and file name aside).
void require_same_model(const ir::ModelIr& a, const ir::ModelIr& b) {
  CHECK(a.name == b.name);
  REQUIRE(a.parameters.size() == b.parameters.size());
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    const ir::Parameter &p = a.parameters[i], &q = b.parameters[i];
    CHECK(p.name == q.name);
    CHECK(text(p.value) == text(q.value));
    CHECK(p.derived == q.derived);
    CHECK(p.unit == q.unit);
    CHECK(p.role == q.role);
    CHECK(text(p.lower) == text(q.lower));
    CHECK(text(p.upper) == text(q.upper));
  }
  REQUIRE(a.grounds.size() == b.grounds.size());
  for (std::size_t i = 0; i < a.grounds.size(); ++i) CHECK(a.grounds[i].name == b.grounds[i].name);
  REQUIRE(a.bodies.size() == b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const ir::Body &p = a.bodies[i], &q = b.bodies[i];
    CHECK(p.name == q.name);
    CHECK(text(p.mass) == text(q.mass));
    for (int k = 0; k < 6; ++k) CHECK(text(p.inertia[k]) == text(q.inertia[k]));
    for (int k = 0; k < 3; ++k) CHECK(text(p.position[k]) == text(q.position[k]));
    CHECK(p.dofs == q.dofs);
  }
  auto same_attachment = [](const ir::Attachment& p, const ir::Attachment& q) {
    CHECK(p.frame == q.frame);
    CHECK(p.has_point == q.has_point);
    for (int k = 0; k < 3; ++k) CHECK(text(p.point[k]) == text(q.point[k]));
  };
  auto same_direction = [](const ir::Direction& p, const ir::Direction& q) {
    CHECK(p.axis == q.axis);
    for (int k = 0; k < 3; ++k) CHECK(text(p.vector[k]) == text(q.vector[k]));
  };
  REQUIRE(a.elements.size() == b.elements.size());
  for (std::size_t i = 0; i < a.elements.size(); ++i) {
    const ir::Element &p = a.elements[i], &q = b.elements[i];
    CHECK(p.name == q.name);
    CHECK(p.kind == q.kind);
    same_attachment(p.a, q.a);
    same_attachment(p.b, q.b);
    if (p.kind != ir::ElementKind::Spring3) same_direction(p.direction, q.direction);
    REQUIRE(p.stiffness.size() == q.stiffness.size());
    for (std::size_t k = 0; k < p.stiffness.size(); ++k) CHECK(text(p.stiffness[k]) == text(q.stiffness[k]));
    REQUIRE(p.damping.size() == q.damping.size());
    for (std::size_t k = 0; k < p.damping.size(); ++k) CHECK(text(p.damping[k]) == text(q.damping[k]));
  }
  REQUIRE(a.spins.size() == b.spins.size());
  for (std::size_t i = 0; i < a.spins.size(); ++i) {
    CHECK(a.spins[i].body == b.spins[i].body);
    CHECK(a.spins[i].axis == b.spins[i].axis);
    CHECK(text(a.spins[i].speed) == text(b.spins[i].speed));
  }
  REQUIRE(a.inputs.size() == b.inputs.size());
  for (std::size_t i = 0; i < a.inputs.size(); ++i) {
    CHECK(a.inputs[i].name == b.inputs[i].name);
    CHECK(a.inputs[i].kind == b.inputs[i].kind);
    if (a.inputs[i].kind == ir::InputKind::Force) same_attachment(a.inputs[i].at, b.inputs[i].at);
    same_direction(a.inputs[i].direction, b.inputs[i].direction);
    CHECK(text(a.inputs[i].gain) == text(b.inputs[i].gain));
  }
  REQUIRE(a.outputs.size() == b.outputs.size());
  for (std::size_t i = 0; i < a.outputs.size(); ++i) {
    CHECK(a.outputs[i].name == b.outputs[i].name);
    CHECK(a.outputs[i].kind == b.outputs[i].kind);
    same_attachment(a.outputs[i].at, b.outputs[i].at);
    same_direction(a.outputs[i].direction, b.outputs[i].direction);
  }
  REQUIRE(a.filters.size() == b.filters.size());
  for (std::size_t i = 0; i < a.filters.size(); ++i) {
    CHECK(a.filters[i].name == b.filters[i].name);
    CHECK(a.filters[i].output == b.filters[i].output);
    CHECK(a.filters[i].kind == b.filters[i].kind);
    CHECK(a.filters[i].sections == b.filters[i].sections);
    for (auto member : {&ir::Filter::cutoff, &ir::Filter::damping, &ir::Filter::time, &ir::Filter::factor}) {
      REQUIRE((a.filters[i].*member).has_value() == (b.filters[i].*member).has_value());
      if ((a.filters[i].*member)) CHECK(ir::to_string(*(a.filters[i].*member)) == ir::to_string(*(b.filters[i].*member)));
    }
  }
}

// Uses every construct of the language: derived parameters, open bounds, six inertias, vector directions,
// torsion, spin, a moment input, all output kinds, implicit and explicit points, `;` separators.
const char* const kEverything = R"(model every_thing
param m = 2 "kg" estimate in [1e-3, inf]
param J = m*(0.1^2 + 0.05^2)/12 "kg m^2"
param Jz = -(-J) fixed
param k = 1.5E-3*2e6 "N/m" in [-inf, 1e9]
param kt = 400
param c = 0 fixed in [0, 10]   # assumed negligible
param n = 25 "rev/s"
ground g; ground g2
body rotor {
  mass m
  inertia J, J, Jz, 0, 0, 0
  at (0, -0.5, 1/3)
  dof x, y rx ry
}
body block { mass 3; inertia 1, 2, 3; dof z rz }
spring s1 { from g at (0, 0, 1); to rotor at (0.1, -0.5, 1/3); along (1, 1, 0); stiffness k; damping c }
spring3 s2 {
  from rotor
  to g2 at (-1, sqrt(2), cos(pi/4))
  stiffness k, 2*k, k^2/k
  damping c, c, c
}
torsion t1 { from rotor; to g; about y; stiffness kt }
torsion t2 { from block; to g; about (0, 0, 1); stiffness kt; damping 0.1 }
spring s3 { from block; to g2; along z; stiffness k }
spring s4 { from block at (1, 0, 0); to rotor; along x; stiffness k }
spin rotor about z speed n
input F force on rotor at (0, 0, 1) along x
input T moment on block along z
input F2 force on block at (1, 0, 0) along z gain -0.98*k/k
output d displacement of rotor along x
output v velocity of block at (1, 2, 3) along (0, 0, -1)
output a acceleration of rotor at (0, 0.1, 0) along y
filter lp on d lowpass2 cutoff 2*n damping 0.7
filter dl on d delay time 1e-3 sections 2
filter hp on a highpass1 cutoff 3; filter hp2 on v highpass2 cutoff 5 damping 1/2
filter cal on v gain factor -1
)";

void check_round_trip(const ir::ModelIr& m) {
  const std::string once = frontend::write_model(m);
  const ir::ModelIr again = frontend::parse_string(once, "written.mdl");
  require_same_model(m, again);
  CHECK(frontend::write_model(again) == once);
}

}  // namespace

TEST_CASE("the examples survive write and parse", "[writer]") {
  for (const char* name : {"mdof2", "spindle"}) {
    INFO(name);
    check_round_trip(frontend::parse_file(mbgen::test::example_model_path(name)));
  }
}

TEST_CASE("every construct of the language survives write and parse", "[writer]") {
  const ir::ModelIr m = frontend::parse_string(kEverything, "every.mdl");
  check_round_trip(m);
  const std::string text = frontend::write_model(m);
  // Spot checks of the syntax itself, against the language description.
  CHECK(text.find("inertia J, J, Jz, 0, 0, 0\n") != std::string::npos);
  CHECK(text.find("  at (0, -0.5, 1/3)\n") != std::string::npos);
  CHECK(text.find("dof x y rx ry\n") != std::string::npos);
  CHECK(text.find("in [1e-3, inf]") != std::string::npos);
  CHECK(text.find("in [-inf, 1e9]") != std::string::npos);
  CHECK(text.find("  to g2 at (-1, sqrt(2), cos(pi/4))\n") != std::string::npos);
  CHECK(text.find("  about (0, 0, 1)\n") != std::string::npos);
  CHECK(text.find("input T moment on block along z\n") != std::string::npos);
  CHECK(text.find("input F2 force on block at (1, 0, 0) along z gain -0.98*k/k\n") != std::string::npos);
  CHECK(text.find("spin rotor about z speed n\n") != std::string::npos);
  CHECK(text.find("output d displacement of rotor along x\n") != std::string::npos);
}

TEST_CASE("parameter declarations line up and keep their comments", "[writer]") {
  ir::Parameter p;
  p.name = "c12";
  p.value = ir::Expr::number("0");
  p.unit = "N s/m";
  p.role = ir::Role::Fixed;
  p.comment = "the helix is undamped";
  CHECK(frontend::write_parameter(p) == "param c12 = 0  \"N s/m\"  fixed  # the helix is undamped\n");
  p.comment.clear();
  p.unit.clear();
  p.role = ir::Role::Known;
  CHECK(frontend::write_parameter(p) == "param c12 = 0\n");
}
