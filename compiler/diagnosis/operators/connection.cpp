// connection:A-B -- two frames the model does not join directly are joined after all (a cable, a seal, a
// forgotten support): a spring3 between their centres of mass (a ground side: at the body's centre of mass).
#include <algorithm>
#include <cmath>

#include "diagnosis/expr_build.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

namespace {

struct Frame {
  std::string name;
  ir::SourceLoc loc;
  const ir::Body* body;  // null for a ground
};

// Grounds and bodies in the order the text declares them.
std::vector<Frame> frames_in_order(const ir::ModelIr& m) {
  std::vector<Frame> out;
  for (const ir::Ground& g : m.grounds) out.push_back({g.name, g.loc, nullptr});
  for (const ir::Body& b : m.bodies) out.push_back({b.name, b.loc, &b});
  std::stable_sort(out.begin(), out.end(), [](const Frame& a, const Frame& b) {
    return a.loc.line != b.loc.line ? a.loc.line < b.loc.line : a.loc.column < b.loc.column;
  });
  return out;
}

bool joined(const ir::ModelIr& m, const std::string& a, const std::string& b) {
  return std::any_of(m.elements.begin(), m.elements.end(), [&](const ir::Element& e) {
    return (e.a.frame == a && e.b.frame == b) || (e.a.frame == b && e.b.frame == a);
  });
}

bool translates(const Frame& f) {
  return f.body && std::any_of(f.body->dofs.begin(), f.body->dofs.end(),
                               [](ir::Dof d) { return d == ir::Dof::X || d == ir::Dof::Y || d == ir::Dof::Z; });
}

double stiffest_element_on(const OperatorInput& in, const std::string& a, const std::string& b) {
  double k = 0;
  for (const ir::Element& e : in.model.elements) {
    if (e.kind == ir::ElementKind::Torsion) continue;
    if (e.a.frame != a && e.b.frame != a && e.a.frame != b && e.b.frame != b) continue;
    for (const ir::Expr& s : e.stiffness) k = std::max(k, in.values.of(s));
  }
  return k > 0 ? k : largest_translational_stiffness(in.model, in.values);
}

Extension extend(const OperatorInput& in, const Frame& a, const Frame& b) {
  Draft d(in, "connection", a.name + "-" + b.name);
  // Start: a tenth of the stiffest spring on either frame; 2 % damping on the lighter body.
  const double k = 0.1 * stiffest_element_on(in, a.name, b.name);
  double mass = INFINITY;
  for (const Frame* f : {&a, &b})
    if (f->body) mass = std::min(mass, in.values.of(f->body->mass));
  const std::string k_ab = d.add_parameter("k_" + a.name + "_" + b.name, k, "N/m", 0.0, std::nullopt,
                                           "stiffness between " + a.name + " and " + b.name + ", each axis");
  const double c = light_damping(k, mass);
  const std::string c_ab = d.add_parameter("c_" + a.name + "_" + b.name, c, "N s/m", 0.0,
                                           std::nullopt, "damping between " + a.name + " and " + b.name + ", each axis");
  d.nests_near_zero(k_ab, k);
  d.nests_near_zero(c_ab, c);
  ir::Element s;
  s.kind = ir::ElementKind::Spring3;
  s.name = d.names().fresh(a.name + "_" + b.name + "_link");
  s.a.frame = a.name;
  s.b.frame = b.name;
  // A body end is its centre of mass (implicit); a ground end sits at the other body's centre of mass.
  const ir::Vec3& where = a.body ? a.body->position : b.body->position;
  s.a.point = where;
  s.a.has_point = !a.body;
  s.b.point = b.body ? b.body->position : where;
  s.b.has_point = !b.body;
  s.stiffness = {sym(k_ab), sym(k_ab), sym(k_ab)};
  s.damping = {sym(c_ab), sym(c_ab), sym(c_ab)};
  d.add_element(s);
  return d.finish(a.name + " and " + b.name + " are joined directly: a spring-damper between them (stiffness " + k_ab +
                  ", damping " + c_ab + " in every direction)");
}

}  // namespace

std::vector<Extension> connection(const OperatorInput& in) {
  std::vector<Extension> out;
  const std::vector<Frame> frames = frames_in_order(in.model);
  for (std::size_t i = 0; i < frames.size(); ++i)
    for (std::size_t j = i + 1; j < frames.size(); ++j) {
      const Frame &a = frames[i], &b = frames[j];
      // At least one body, and one that translates: a spring3 acts on translations only.
      if (!translates(a) && !translates(b)) continue;
      if (joined(in.model, a.name, b.name)) continue;
      out.push_back(extend(in, a, b));
    }
  return out;
}

}  // namespace mbgen::diagnosis
