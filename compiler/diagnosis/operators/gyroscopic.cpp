// gyroscopic:B -- a body that turns freely about one axis (it lacks exactly that rotation coordinate) and is
// axisymmetric about it spins at a speed the model has a parameter for: add the `spin` statement, which
// couples its two tilting motions (thesis Sec. 5.4.2.1 neglected this).
#include <algorithm>

#include "diagnosis/expr_build.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

namespace {

// The spin speed: a parameter in rev/s that the data sets vary, else one with a non-zero value. A speed that is
// zero everywhere would make the spin do nothing.
std::optional<std::string> spin_speed(const OperatorInput& in) {
  std::optional<std::string> nonzero;
  for (const ir::Parameter& p : in.model.parameters) {
    if (p.unit != "rev/s") continue;
    if (in.ctx.varying_parameters.count(p.name)) return p.name;
    if (!nonzero && in.values.of_parameter(p.name) != 0.0) nonzero = p.name;
  }
  return nonzero;
}

// The axis (0, 1, 2) a body turns freely about: the one rotation it lacks, if it has the other two.
std::optional<int> free_rotation_axis(const ir::Body& b) {
  std::optional<int> missing;
  for (int k = 0; k < 3; ++k)
    if (!has_dof(b, static_cast<ir::Dof>(3 + k))) {
      if (missing) return std::nullopt;
      missing = k;
    }
  return missing;
}

// Axisymmetric about `axis`: the two transverse inertias are written as the same expression (derived parameters
// expanded) and are not zero, and no product of inertia is.
bool axisymmetric(const OperatorInput& in, const ir::Body& b, int axis) {
  const int t1 = axis == 0 ? 1 : 0, t2 = axis == 2 ? 1 : 2;
  if (!b.inertia[t1] || !b.inertia[t2]) return false;
  if (!same_expr(expand_derived(in.model, *b.inertia[t1]), expand_derived(in.model, *b.inertia[t2]))) return false;
  if (in.values.of(*b.inertia[t1]) == 0.0) return false;
  for (int k = 3; k < 6; ++k)
    if (b.inertia[k] && in.values.of(*b.inertia[k]) != 0.0) return false;
  return true;
}

}  // namespace

std::vector<Extension> gyroscopic(const OperatorInput& in) {
  std::vector<Extension> out;
  const std::optional<std::string> speed = spin_speed(in);
  if (!speed) return out;
  for (const ir::Body& b : in.model.bodies) {
    const bool spinning = std::any_of(in.model.spins.begin(), in.model.spins.end(),
                                      [&](const ir::Spin& s) { return s.body == b.name; });
    const std::optional<int> axis = free_rotation_axis(b);
    if (spinning || !axis || !axisymmetric(in, b, *axis)) continue;
    Draft d(in, "gyroscopic", b.name);
    ir::Spin s;
    s.body = b.name;
    s.axis = std::string(1, "xyz"[*axis]);
    s.speed = sym(*speed);
    d.add_spin(s);
    out.push_back(d.finish(b.name + " spins about " + s.axis + " at " + *speed +
                           " rev/s: its two tilting motions are coupled gyroscopically"));
  }
  return out;
}

}  // namespace mbgen::diagnosis
