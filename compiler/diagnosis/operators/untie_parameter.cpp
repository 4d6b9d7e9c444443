// untie_parameter:P -- one estimated parameter written into several elements (four mounts sharing one
// stiffness) says they are identical; this candidate lets each element have its own copy.
#include <algorithm>

#include "diagnosis/expr_build.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

namespace {

// The expressions of an element that its text writes: stiffness, damping, explicit points, a vector direction.
// (An implicit point is the body's centre of mass: it belongs to the body, not to the element.)
std::vector<ir::Expr*> written_expressions(ir::Element& e) {
  std::vector<ir::Expr*> out;
  for (ir::Expr& k : e.stiffness) out.push_back(&k);
  for (ir::Expr& c : e.damping) out.push_back(&c);
  for (ir::Attachment* a : {&e.a, &e.b})
    if (a->has_point)
      for (ir::Expr& p : a->point) out.push_back(&p);
  if (e.direction.axis.empty() && e.kind != ir::ElementKind::Spring3)
    for (ir::Expr& v : e.direction.vector) out.push_back(&v);
  return out;
}

bool uses(const ir::Expr& e, const std::string& name) {
  const std::vector<std::string> s = ir::symbols_of(e);
  return std::find(s.begin(), s.end(), name) != s.end();
}

bool element_uses(const ir::Element& e, const std::string& name) {
  ir::Element copy = e;
  for (const ir::Expr* x : written_expressions(copy))
    if (uses(*x, name)) return true;
  return false;
}

// Renames `from` to `to` in the tree, recording where each occurrence was in the text.
void rename(ir::Expr& e, const std::string& from, const std::string& to, std::vector<ir::SourceLoc>& locs) {
  if (e.kind == ir::Expr::Kind::Symbol && e.text == from) {
    locs.push_back(e.loc);
    e.text = to;
  }
  for (ir::Expr& a : e.args) rename(a, from, to, locs);
}

// Whether anything but elements (parameters, bodies, spins, signals' written points and directions) uses it.
bool used_outside_elements(const ir::Model& m, const std::string& name) {
  for (const ir::Parameter& p : m.parameters)
    if (uses(p.value, name) || (p.lower && uses(*p.lower, name)) || (p.upper && uses(*p.upper, name))) return true;
  for (const ir::Body& b : m.bodies) {
    if (uses(b.mass, name)) return true;
    for (const auto& j : b.inertia)
      if (j && uses(*j, name)) return true;
    for (const ir::Expr& x : b.position)
      if (uses(x, name)) return true;
  }
  for (const ir::Spin& s : m.spins)
    if (uses(s.speed, name)) return true;
  auto signal_uses = [&](const ir::Attachment& a, const ir::Direction& d) {
    for (int k = 0; k < 3; ++k)
      if ((a.has_point && uses(a.point[k], name)) || (d.axis.empty() && uses(d.vector[k], name))) return true;
    return false;
  };
  for (const ir::Input& in : m.inputs)
    if (signal_uses(in.at, in.direction)) return true;
  for (const ir::Output& out : m.outputs)
    if (signal_uses(out.at, out.direction)) return true;
  return false;
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

Extension untie(const OperatorInput& in, const ir::Parameter& p) {
  Draft d(in, "untie_parameter", p.name);
  ir::Model& x = d.model();
  const bool overridden = in.ctx.values.count(p.name) > 0;
  std::vector<std::string> copies, users;
  for (ir::Element& e : x.elements) {
    if (!element_uses(e, p.name)) continue;
    // Each copy starts where P is now (its fitted value if there is one), with P's unit and bounds.
    ir::Parameter copy = p;
    copy.name = d.names().fresh(p.name + "_" + e.name);
    copy.value = overridden ? number_expr(in.values.of_parameter(p.name)) : p.value;
    copy.role = ir::Role::Estimate;
    copy.comment.clear();
    copy.loc = {};
    copies.push_back(copy.name);
    users.push_back(e.name);
    std::vector<ir::SourceLoc> locs;
    for (ir::Expr* ex : written_expressions(e)) rename(*ex, p.name, copy.name, locs);
    for (const ir::SourceLoc& loc : locs) d.patch().rename(loc, p.name, copy.name);
    d.add_parameter(copy, p.name + " as seen by " + e.name);
  }
  if (!used_outside_elements(x, p.name)) {
    x.parameters.erase(std::find_if(x.parameters.begin(), x.parameters.end(),
                                    [&](const ir::Parameter& q) { return q.name == p.name; }));
    d.patch().replace_statement(p.loc, p.name + " is no longer used: each element has its own copy", "");
  }
  return d.finish("the elements " + join(users) + " share " + p.name + "; each gets its own copy (" + join(copies) +
                  ") so that they may differ");
}

}  // namespace

std::vector<Extension> untie_parameter(const OperatorInput& in) {
  std::vector<Extension> out;
  for (const ir::Parameter& p : in.model.parameters) {
    if (p.role != ir::Role::Estimate || p.derived) continue;
    const auto users = std::count_if(in.model.elements.begin(), in.model.elements.end(),
                                     [&](const ir::Element& e) { return element_uses(e, p.name); });
    if (users >= 2) out.push_back(untie(in, p));
  }
  return out;
}

}  // namespace mbgen::diagnosis
