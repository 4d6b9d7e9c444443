// added_mass:B -- a mass the model leaves out sits where body B is excited or measured (a sensor, a stinger,
// a load cell): B's mass, centre of mass and inertia change as for a point mass ma_B at that point.
#include <algorithm>

#include "diagnosis/expr_build.hpp"
#include "frontend/model_writer.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

namespace {

// B with a point mass `ma` at `p`, all as expressions. With r = p - c (c the old centre of mass):
//   mass m + ma,  centre c + ma/(m + ma) r,  inertia I + mu (|r|^2 E - r r^T) with mu = m ma/(m + ma)
// (the parallel-axis theorem for both masses about their common centre collapses to the reduced mass mu).
ir::Body with_point_mass(const ir::Body& b, const ir::Vec3& p, const std::string& ma) {
  ir::Body out = b;
  const ir::Expr m = b.mass;
  const ir::Expr total = add(m, sym(ma));
  out.mass = total;
  ir::Vec3 r;
  for (int k = 0; k < 3; ++k) r[k] = same_expr(p[k], b.position[k]) ? num("0") : sub(p[k], b.position[k]);
  for (int k = 0; k < 3; ++k)
    if (!is_zero_literal(r[k])) out.position[k] = add(b.position[k], div(mul(sym(ma), r[k]), total));
  const ir::Expr mu = div(mul(m, sym(ma)), total);
  // Diagonal: I_kk + mu (r_i^2 + r_j^2); products I_ij - mu r_i r_j (order xy, xz, yz).
  const int others[3][2] = {{1, 2}, {0, 2}, {0, 1}};
  const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int k = 0; k < 6; ++k) {
    const ir::Expr old = b.inertia[k] ? *b.inertia[k] : num("0");
    const ir::Expr term =
        k < 3 ? mul(mu, add(square(r[others[k][0]]), square(r[others[k][1]])))
              : mul(mu, mul(r[pairs[k - 3][0]], r[pairs[k - 3][1]]));
    if (is_zero_literal(term)) continue;
    out.inertia[k] = k < 3 ? add(old, term) : sub(old, term);
  }
  // As the writer writes it: with any inertia all three moments, with any product all three products.
  const bool any = std::any_of(out.inertia.begin(), out.inertia.end(), [](const auto& j) { return j.has_value(); });
  const bool products = out.inertia[3] || out.inertia[4] || out.inertia[5];
  for (int k = 0; k < 6; ++k)
    if (!out.inertia[k] && (k < 3 ? any : products)) out.inertia[k] = num("0");
  return out;
}

bool moves_off_spin_axis(const OperatorInput& in, const ir::Body& b, const ir::Vec3& p) {
  for (const ir::Spin& s : in.model.spins) {
    if (s.body != b.name) continue;
    const int axis = s.axis == "x" ? 0 : s.axis == "y" ? 1 : 2;
    for (int k = 0; k < 3; ++k)
      if (k != axis && in.values.of(p[k]) != in.values.of(b.position[k])) return true;
  }
  return false;
}

Extension extend(const OperatorInput& in, std::size_t index, const SignalPoint& at) {
  const ir::Body& b = in.model.bodies[index];
  Draft d(in, "added_mass", b.name);
  const double mass = in.values.of(b.mass);
  const std::string ma = d.add_parameter("ma_" + b.name, 0.01 * mass, "kg", 0.0, mass,
                                         "mass added to " + b.name + " at " + at.signal);
  const ir::Body moved = with_point_mass(b, at.at->point, ma);
  d.model().bodies[index] = moved;
  d.patch().replace_statement(b.loc, "a mass " + ma + " at the point of " + at.signal,
                              frontend::write_body(moved));

  // Where the text meant B's centre of mass without writing it, it keeps meaning the old one.
  bool shifted = false;
  for (int k = 0; k < 3; ++k) shifted = shifted || !same_expr(moved.position[k], b.position[k]);
  if (shifted) {
    const std::string old_centre = " at " + frontend::write_vec3(b.position);
    auto pin = [&](ir::Attachment& a) {
      if (a.frame != b.name || a.has_point) return;
      a.has_point = true;
      d.patch().insert_after(a.loc, b.name, old_centre);
    };
    for (ir::Element& e : d.model().elements)
      if (e.kind != ir::ElementKind::Torsion) {  // a torsion's ends have no point
        pin(e.a);
        pin(e.b);
      }
    for (ir::Input& i : d.model().inputs)
      if (i.kind == ir::InputKind::Force) pin(i.at);  // a moment's point means nothing
    for (ir::Output& o : d.model().outputs) pin(o.at);
  }
  return d.finish("a mass " + ma + " (a sensor, stinger or load cell) sits on " + b.name + " at the point of " +
                  std::string(at.is_input ? "input " : "output ") + at.signal +
                  "; the body's mass, centre of mass and inertia change accordingly");
}

}  // namespace

std::vector<Extension> added_mass(const OperatorInput& in) {
  std::vector<Extension> out;
  for (std::size_t i = 0; i < in.model.bodies.size(); ++i) {
    const ir::Body& b = in.model.bodies[i];
    const std::optional<SignalPoint> at = signal_point(in.model, b.name);
    // An off-axis mass would break the axisymmetry a spinning body needs.
    if (!at || moves_off_spin_axis(in, b, at->at->point)) continue;
    out.push_back(extend(in, i, *at));
  }
  return out;
}

}  // namespace mbgen::diagnosis
