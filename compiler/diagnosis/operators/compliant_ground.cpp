// compliant_ground:G -- a ground that elements attach to is not rigid after all (thesis Sec. 5.4.3: an
// unexplained 190 Hz peak, "possibly the table" the spindle housing stands on). It becomes a body that moves
// in translation, held to a new fixed ground by one isotropic spring-damper.
#include <algorithm>
#include <cmath>

#include "diagnosis/expr_build.hpp"
#include "frontend/model_writer.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

namespace {

// The translations the attached elements act along: a spring's axis, all three for a spring3 or an oblique
// spring. Torsions act on rotations, which the new body does not get.
std::vector<ir::Dof> translations_needed(const ir::Model& m, const std::string& ground, const ModelValues& values) {
  bool axis[3] = {false, false, false};
  for (const ir::Element& e : m.elements) {
    if (e.a.frame != ground && e.b.frame != ground) continue;
    if (e.kind == ir::ElementKind::Spring3) axis[0] = axis[1] = axis[2] = true;
    if (e.kind != ir::ElementKind::Spring) continue;
    if (const std::optional<int> k = axis_of(e.direction, values)) axis[*k] = true;
    else axis[0] = axis[1] = axis[2] = true;
  }
  std::vector<ir::Dof> dofs;
  for (int k = 0; k < 3; ++k)
    if (axis[k]) dofs.push_back(static_cast<ir::Dof>(k));
  return dofs;
}

// Bodies declared before `loc` in the text: where the parser will put a body declared at `loc`.
std::size_t bodies_before(const ir::Model& m, ir::SourceLoc loc) {
  return std::count_if(m.bodies.begin(), m.bodies.end(), [&](const ir::Body& b) {
    return b.loc.line < loc.line || (b.loc.line == loc.line && b.loc.column < loc.column);
  });
}

Extension extend(const OperatorInput& in, const ir::Ground& ground) {
  const ir::Model& m = in.model;
  Draft d(in, "compliant_ground", ground.name);

  // Centroid and spread of the attachment points, at the current values.
  std::vector<std::array<double, 3>> points;
  for (const ir::Element& e : m.elements)
    for (const ir::Attachment* a : {&e.a, &e.b})
      if (a->frame == ground.name)
        points.push_back({in.values.of(a->point[0]), in.values.of(a->point[1]), in.values.of(a->point[2])});
  std::array<double, 3> centre{0, 0, 0};
  for (const auto& p : points)
    for (int k = 0; k < 3; ++k) centre[k] += p[k] / points.size();
  // Rounding must not turn a centred layout into a 1e-18 offset.
  double scale = 1;
  for (const auto& p : points)
    for (double v : p) scale = std::max(scale, std::abs(v));
  for (double& c : centre)
    if (std::abs(c) < 1e-12 * scale) c = 0;
  double radius = 0;
  for (const auto& p : points)
    radius = std::max(radius, std::hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]));
  const bool centred = centre == std::array<double, 3>{0, 0, 0};

  // Start values: a few times the moving mass; the new mode at the strongest unexplained peak, else well above
  // the model's own modes (twice the frequency sqrt(k_max/m_min) of its stiffest element on its lightest body).
  const double total = total_moving_mass(m, in.values);
  const double mass = 3 * total;
  const double omega = in.ctx.peak_hz.empty()
                           ? 2 * std::sqrt(largest_translational_stiffness(m, in.values) / smallest_body_mass(m, in.values))
                           : kTwoPi * in.ctx.peak_hz.front();
  const double k = mass * omega * omega;
  const std::string& g = ground.name;
  const std::string m_g = d.add_parameter("m_" + g, mass, "kg", 1e-3 * total, 1e3 * total, "mass of " + g + " when it moves");
  const std::string k_g = d.add_parameter("k_" + g, k, "N/m", 0.0, std::nullopt, "stiffness holding " + g + ", each axis");
  const std::string c_g = d.add_parameter("c_" + g, light_damping(k, mass), "N s/m", 0.0, std::nullopt,
                                          "damping holding " + g + ", each axis");

  ir::Body body;
  body.name = g;
  body.mass = sym(m_g);
  if (radius > 0) {
    // A rigid block of the size the attachments span: inertia of a solid sphere of that radius, known.
    const std::string r_g = d.add_parameter("r_" + g, radius, "m", std::nullopt, std::nullopt,
                                            "size of " + g + ": farthest attachment from their centroid", ir::Role::Known);
    for (int j = 0; j < 3; ++j) body.inertia[j] = div(mul(mul(num("2"), sym(m_g)), square(sym(r_g))), num("5"));
  }
  for (int j = 0; j < 3; ++j) body.position[j] = number_expr(centre[j]);
  body.dofs = translations_needed(m, g, in.values);

  ir::Model& x = d.model();
  x.grounds.erase(std::find_if(x.grounds.begin(), x.grounds.end(), [&](const ir::Ground& q) { return q.name == g; }));
  x.bodies.insert(x.bodies.begin() + bodies_before(m, ground.loc), body);
  d.patch().replace_statement(ground.loc, "ground `" + g + "` now moves: it is a body held by spring-dampers",
                              frontend::write_body(body));

  // Attachments that meant the ground's origin keep that point (a body's implicit point is its centre of mass).
  for (ir::Element& e : x.elements)
    for (ir::Attachment* a : {&e.a, &e.b})
      if (a->frame == g && !a->has_point && !centred && e.kind != ir::ElementKind::Torsion) {
        a->has_point = true;
        d.patch().insert_after(a->loc, g, " at (0, 0, 0)");
      }

  ir::Ground fixed{d.names().fresh(g + "_fixed"), {}};
  d.add_ground(fixed);
  ir::Element support;
  support.name = d.names().fresh(g + "_support");
  support.kind = ir::ElementKind::Spring3;
  support.a.frame = g;
  support.a.point = body.position;
  support.b.frame = fixed.name;
  support.b.point = body.position;
  support.b.has_point = !centred;
  support.stiffness = {sym(k_g), sym(k_g), sym(k_g)};
  support.damping = {sym(c_g), sym(c_g), sym(c_g)};
  d.add_element(support);

  return d.finish("ground " + g + " is not rigid: it becomes a body of mass " + m_g + " held to a fixed " + fixed.name +
                  " by springs of stiffness " + k_g + " and damping " + c_g + " in every direction");
}

}  // namespace

std::vector<Extension> compliant_ground(const OperatorInput& in) {
  std::vector<Extension> out;
  for (const ir::Ground& g : in.model.grounds) {
    const bool held = std::any_of(in.model.elements.begin(), in.model.elements.end(), [&](const ir::Element& e) {
      return e.kind != ir::ElementKind::Torsion && (e.a.frame == g.name || e.b.frame == g.name);
    });
    if (held) out.push_back(extend(in, g));
  }
  return out;
}

}  // namespace mbgen::diagnosis
