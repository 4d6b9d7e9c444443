// moment_stiffness:E -- a spring-damper that the model lets resist only translation (a bearing, a mount)
// also resists tilting: torsion elements about the axes across it, sharing one stiffness and one damping.
#include <algorithm>
#include <cmath>

#include "diagnosis/expr_build.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

namespace {

// Whether a frame takes part in a rotation about `axis` (0, 1, 2) in a way a torsion may act on: a ground
// (its rotation is zero) or a body with that rotation coordinate. A body *without* the coordinate is left out:
// it may be guided (rotation zero) or turn freely (the spindle about its own axis); a torsion would tie the
// other frame to it either way, which is wrong in the second case.
bool takes_part(const ir::ModelIr& m, const std::string& frame, int axis) {
  if (m.is_ground(frame)) return true;
  return has_dof(*m.find_body(frame), static_cast<ir::Dof>(3 + axis));
}

std::vector<int> torsion_axes(const OperatorInput& in, const ir::Element& e) {
  std::vector<int> across;
  if (e.kind == ir::ElementKind::Spring3) {
    across = {0, 1, 2};
  } else {
    const std::optional<int> along = axis_of(e.direction, in.values);
    if (!along) return {};  // an oblique spring: no axis-aligned torsions describe its bending
    for (int k = 0; k < 3; ++k)
      if (k != *along) across.push_back(k);
  }
  std::vector<int> axes;
  for (int k : across)
    if (takes_part(in.model, e.a.frame, k) && takes_part(in.model, e.b.frame, k)) axes.push_back(k);
  return axes;
}

double largest(const std::vector<ir::Expr>& values, const ModelValues& v) {
  double out = 0;
  for (const ir::Expr& x : values) out = std::max(out, v.of(x));
  return out;
}

// "x", "x and y", "x, y and z".
std::string listing(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return out;
}

Extension extend(const OperatorInput& in, const ir::Element& e, const std::vector<int>& axes) {
  Draft d(in, "moment_stiffness", e.name);
  // Start: the element's stiffness (damping) times the square of its length, 10 mm if its ends coincide.
  double length = 0;
  for (int k = 0; k < 3; ++k) length += std::pow(in.values.of(e.a.point[k]) - in.values.of(e.b.point[k]), 2);
  length = std::sqrt(length);
  if (length < 1e-9) length = 0.01;
  const double l2 = length * length;
  const double kr_start = largest(e.stiffness, in.values) * l2, cr_start = largest(e.damping, in.values) * l2;
  const std::string kr =
      d.add_parameter("kr_" + e.name, kr_start, "N m/rad", 0.0, std::nullopt, "rotational stiffness of " + e.name);
  const std::string cr =
      d.add_parameter("cr_" + e.name, cr_start, "N m s/rad", 0.0, std::nullopt, "rotational damping of " + e.name);
  d.nests_near_zero(kr, kr_start);
  d.nests_near_zero(cr, cr_start);
  std::vector<std::string> about;
  for (int k : axes) {
    ir::Element t;
    t.kind = ir::ElementKind::Torsion;
    t.name = d.names().fresh(e.name + "_r" + std::string(1, "xyz"[k]));
    t.a.frame = e.a.frame;
    t.b.frame = e.b.frame;
    // Implicit points, as the parser fills them (a torsion has no point).
    const ir::Body* a = in.model.find_body(e.a.frame);
    const ir::Body* b = in.model.find_body(e.b.frame);
    t.a.point = a ? a->position : ir::Vec3{num("0"), num("0"), num("0")};
    t.b.point = b ? b->position : ir::Vec3{num("0"), num("0"), num("0")};
    t.direction.axis = std::string(1, "xyz"[k]);
    for (int j = 0; j < 3; ++j) t.direction.vector[j] = num(j == k ? "1" : "0");
    t.stiffness = {sym(kr)};
    t.damping = {sym(cr)};
    d.add_element(t);
    about.push_back(t.direction.axis);
  }
  return d.finish(e.name + " also resists tilting between " + e.a.frame + " and " + e.b.frame + ": torsion about " +
                  listing(about) + " with stiffness " + kr + " and damping " + cr);
}

}  // namespace

std::vector<Extension> moment_stiffness(const OperatorInput& in) {
  std::vector<Extension> out;
  for (const ir::Element& e : in.model.elements) {
    if (e.kind == ir::ElementKind::Torsion) continue;
    const std::vector<int> axes = torsion_axes(in, e);
    if (!axes.empty()) out.push_back(extend(in, e, axes));
  }
  return out;
}

}  // namespace mbgen::diagnosis
