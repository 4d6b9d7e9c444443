// Fuzz target: model text -> parser, checks, and the exact values of every expression in the model: parameters and
// bounds (the number limits of docs/limits.md) and the fields of bodies, elements, spins, inputs, outputs and filters
// (which must have a value at the parameters' values). Bad input must end in frontend::ModelError; anything else (a
// crash, a sanitizer report, another exception, a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"
#include "symbolic/to_ginac.hpp"

namespace {

void convert_all(const mbgen::symbolic::ParameterTable& table, const mbgen::ir::ModelIr& model) {
  auto vector = [&](const mbgen::ir::Vec3& v) {
    for (const mbgen::ir::Expr& x : v) table.convert(x);
  };
  auto point = [&](const mbgen::ir::Attachment& a) {
    if (a.has_point) vector(a.point);
  };
  for (const mbgen::ir::Parameter& p : model.parameters) {
    table.convert(p.value);
    if (p.lower) table.convert(*p.lower);
    if (p.upper) table.convert(*p.upper);
  }
  for (const mbgen::ir::Body& b : model.bodies) {
    table.convert(b.mass);
    for (const auto& i : b.inertia)
      if (i) table.convert(*i);
    vector(b.position);
  }
  for (const mbgen::ir::Element& e : model.elements) {
    point(e.a);
    point(e.b);
    if (e.kind != mbgen::ir::ElementKind::Spring3) vector(e.direction.vector);
    for (const mbgen::ir::Expr& k : e.stiffness) table.convert(k);
    for (const mbgen::ir::Expr& c : e.damping) table.convert(c);
  }
  for (const mbgen::ir::Spin& s : model.spins) table.convert(s.speed);
  for (const mbgen::ir::Input& i : model.inputs) point(i.at), vector(i.direction.vector);
  for (const mbgen::ir::Output& o : model.outputs) point(o.at), vector(o.direction.vector);
  for (const mbgen::ir::Filter& f : model.filters)
    for (const auto* x : {&f.cutoff, &f.damping, &f.time, &f.factor})
      if (*x) table.convert(**x);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const mbgen::ir::ModelIr model = mbgen::frontend::parse_string(text, "fuzz.mdl");
    const mbgen::symbolic::ParameterTable table(model);
    convert_all(table, model);
  } catch (const mbgen::frontend::ModelError&) {
  }
  return 0;
}
