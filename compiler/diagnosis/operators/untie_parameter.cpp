// untie_parameter:P -- one estimated parameter written into several elements (four mounts sharing one
// stiffness) says they are identical; this candidate lets one of them differ. It has one variant per element
// (Extension::variant names it); the diagnosis fits them all and reports the best under the one id.
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

// Variant of the candidate in which the single element `element` gets its own copy `P_<element>`, with P's unit
// and bounds; the other elements keep sharing P.
Extension untie_one(const OperatorInput& in, const ir::Parameter& p, const std::string& element, std::size_t users) {
  Draft d(in, "untie_parameter", p.name);
  ir::ModelIr& x = d.model();
  ir::Parameter copy = p;
  copy.name = d.names().fresh(p.name + "_" + element);
  // The copy starts at half of P's current value: a loose element (a loosened bolt, a worn mount) is the usual
  // way one of several identical elements differs, and at P itself the model is symmetric again, where the
  // data's sensitivity to the copy can vanish (an asymmetry that couples otherwise separate motions acts on
  // the response to second order), so a search started there need not move.
  copy.value = number_expr(0.5 * in.values.of_parameter(p.name));
  copy.role = ir::Role::Estimate;
  copy.comment.clear();
  copy.loc = {};
  for (ir::Element& e : x.elements) {
    if (e.name != element) continue;
    std::vector<ir::SourceLoc> locs;
    for (ir::Expr* ex : written_expressions(e)) rename(*ex, p.name, copy.name, locs);
    for (const ir::SourceLoc& loc : locs) d.patch().rename(loc, p.name, copy.name);
  }
  d.add_parameter(copy, p.name + " as seen by " + element);
  d.nests_at(copy.name, in.values.of_parameter(p.name));
  d.set_variant(element);
  const std::string others = users == 2 ? "the other element keeps " + p.name
                                        : "the other " + std::to_string(users - 1) + " keep sharing " + p.name;
  return d.finish(element + " gets its own " + p.name + " (" + copy.name + "), so that it may differ; " + others);
}

}  // namespace

std::vector<Extension> untie_parameter(const OperatorInput& in) {
  std::vector<Extension> out;
  for (const ir::Parameter& p : in.model.parameters) {
    if (p.role != ir::Role::Estimate || p.derived) continue;
    const auto users = std::count_if(in.model.elements.begin(), in.model.elements.end(),
                                     [&](const ir::Element& e) { return element_uses(e, p.name); });
    if (users < 2) continue;
    // One element at a time: a single element that differs (one loose mount) adds one parameter the data can
    // determine, where a copy for every element would add several that the data may see only as a sum. With
    // two users, freeing either one is the same model.
    for (const ir::Element& e : in.model.elements) {
      if (!element_uses(e, p.name)) continue;
      out.push_back(untie_one(in, p, e.name, static_cast<std::size_t>(users)));
      if (users == 2) break;
    }
  }
  return out;
}

}  // namespace mbgen::diagnosis
