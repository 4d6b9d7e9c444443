// compliant_ground:G -- a ground that elements attach to is not rigid after all (thesis Sec. 5.4.3: an
// unexplained 190 Hz peak, "possibly the table" the spindle housing stands on). Two variants, BIC chooses:
//
//   simple        G becomes a body that moves in translation, held to a new fixed ground by one isotropic
//                 spring-damper at the centroid of its attachments: a base that moves as a whole.
//   on feet       G becomes a rigid block with all six coordinates below what it carries: the attachments on its
//                 top face, its feet at its bottom (a spring3 below each attachment point, per-axis stiffness and
//                 damping shared by the feet), its centre of mass halfway, the depth estimated; a radius of
//                 gyration per axis. A heavy base rocks as well as translates, and its rocking couples into the
//                 structure through the attachment points' offsets. Offered where the attachment points are at
//                 least three and not on one line (else the feet cannot hold the rotations).
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "diagnosis/expr_build.hpp"
#include "frontend/model_writer.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

namespace {

// The translations the attached elements act along: a spring's axis, all three for a spring3 or an oblique
// spring. Torsions act on rotations, which the new body does not get.
std::vector<ir::Dof> translations_needed(const ir::ModelIr& m, const std::string& ground, const ModelValues& values) {
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
std::size_t bodies_before(const ir::ModelIr& m, ir::SourceLoc loc) {
  return std::count_if(m.bodies.begin(), m.bodies.end(), [&](const ir::Body& b) {
    return b.loc.line < loc.line || (b.loc.line == loc.line && b.loc.column < loc.column);
  });
}

// The attachment points of a ground (at the current values), and their centroid and spread.
struct Attachments {
  std::vector<std::array<double, 3>> points;  // one per attachment, repeats included
  std::vector<std::array<double, 3>> distinct;
  std::array<double, 3> centre{0, 0, 0};
  double radius = 0;     // farthest point from the centroid
  bool centred = false;  // the centroid is the origin
};

Attachments attachments_of(const OperatorInput& in, const std::string& ground) {
  Attachments a;
  for (const ir::Element& e : in.model.elements)
    for (const ir::Attachment* at : {&e.a, &e.b})
      if (at->frame == ground)
        a.points.push_back({in.values.of(at->point[0]), in.values.of(at->point[1]), in.values.of(at->point[2])});
  for (const auto& p : a.points)
    for (int k = 0; k < 3; ++k) a.centre[k] += p[k] / a.points.size();
  // Rounding must not turn a centred layout into a 1e-18 offset.
  double scale = 1;
  for (const auto& p : a.points)
    for (double v : p) scale = std::max(scale, std::abs(v));
  for (double& c : a.centre)
    if (std::abs(c) < 1e-12 * scale) c = 0;
  for (const auto& p : a.points) {
    a.radius = std::max(a.radius, std::hypot(p[0] - a.centre[0], p[1] - a.centre[1], p[2] - a.centre[2]));
    const bool seen = std::any_of(a.distinct.begin(), a.distinct.end(), [&](const auto& q) {
      return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) <= 1e-9 * scale;
    });
    if (!seen) a.distinct.push_back(p);
  }
  a.centred = a.centre == std::array<double, 3>{0, 0, 0};
  return a;
}

// At least three distinct points not on one line: feet there hold every rotation.
bool spans_a_plane(const std::vector<std::array<double, 3>>& p) {
  for (std::size_t i = 1; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double u[3] = {p[i][0] - p[0][0], p[i][1] - p[0][1], p[i][2] - p[0][2]};
      const double v[3] = {p[j][0] - p[0][0], p[j][1] - p[0][1], p[j][2] - p[0][2]};
      const double c = std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
      if (c > 1e-9 * std::hypot(u[0], u[1], u[2]) * std::hypot(v[0], v[1], v[2])) return true;
    }
  return false;
}

ir::Vec3 point_expr(const std::array<double, 3>& p) {
  return {number_expr(p[0]), number_expr(p[1]), number_expr(p[2])};
}

// The ground replaced by `body` in the model and in the text; attachments that meant the ground's origin keep
// that point (a body's implicit point is its centre of mass). Returns the new fixed ground's name.
std::string ground_to_body(Draft& d, const OperatorInput& in, const ir::Ground& ground, const ir::Body& body,
                           bool centred) {
  const std::string& g = ground.name;
  ir::ModelIr& x = d.model();
  x.grounds.erase(std::find_if(x.grounds.begin(), x.grounds.end(), [&](const ir::Ground& q) { return q.name == g; }));
  x.bodies.insert(x.bodies.begin() + bodies_before(in.model, ground.loc), body);
  d.patch().replace_statement(ground.loc, "ground `" + g + "` now moves: it is a body held by spring-dampers",
                              frontend::write_body(body));
  for (ir::Element& e : x.elements)
    for (ir::Attachment* a : {&e.a, &e.b})
      if (a->frame == g && !a->has_point && !centred && e.kind != ir::ElementKind::Torsion) {
        a->has_point = true;
        d.patch().insert_after(a->loc, g, " at (0, 0, 0)");
      }
  ir::Ground fixed{d.names().fresh(g + "_fixed"), {}};
  d.add_ground(fixed);
  return fixed.name;
}

// A spring3 from `body` at `point` to the fixed ground at the same point. `body_point_written`: the point is not the
// body's centre of mass (a foot), so the text must say where it is.
ir::Element spring3(const std::string& name, const std::string& body, const std::string& fixed, const ir::Vec3& point,
                    bool body_point_written, bool fixed_point_written, std::vector<ir::Expr> k,
                    std::vector<ir::Expr> c) {
  ir::Element e;
  e.name = name;
  e.kind = ir::ElementKind::Spring3;
  e.a.frame = body;
  e.a.point = point;
  e.a.has_point = body_point_written;
  e.b.frame = fixed;
  e.b.point = point;
  e.b.has_point = fixed_point_written;
  e.stiffness = std::move(k);
  e.damping = std::move(c);
  return e;
}

// Start values: a few times the moving mass; the new mode at the strongest unexplained peak, else well above the
// model's own modes (twice the frequency sqrt(k_max/m_min) of its stiffest element on its lightest body).
struct Start {
  double total, mass, omega;
};
Start start_values(const OperatorInput& in) {
  const ir::ModelIr& m = in.model;
  const double total = total_moving_mass(m, in.values);
  const double omega = in.ctx.peak_hz.empty()
                           ? 2 * std::sqrt(largest_translational_stiffness(m, in.values) / smallest_body_mass(m, in.values))
                           : kTwoPi * in.ctx.peak_hz.front();
  return {total, 3 * total, omega};
}

Extension simple(const OperatorInput& in, const ir::Ground& ground, const Attachments& at, bool with_variants) {
  const ir::ModelIr& m = in.model;
  Draft d(in, "compliant_ground", ground.name);
  if (with_variants) d.set_variant("simple");
  const Start st = start_values(in);
  const double k = st.mass * st.omega * st.omega;
  const std::string& g = ground.name;
  const std::string m_g =
      d.add_parameter("m_" + g, st.mass, "kg", 1e-3 * st.total, 1e3 * st.total, "mass of " + g + " when it moves");
  const std::string k_g = d.add_parameter("k_" + g, k, "N/m", 0.0, std::nullopt, "stiffness holding " + g + ", each axis");
  const std::string c_g = d.add_parameter("c_" + g, light_damping(k, st.mass), "N s/m", 0.0, std::nullopt,
                                          "damping holding " + g + ", each axis");

  ir::Body body;
  body.name = g;
  body.mass = sym(m_g);
  if (at.radius > 0) {
    // A rigid block of the size the attachments span: inertia of a solid sphere of that radius, known.
    const std::string r_g = d.add_parameter("r_" + g, at.radius, "m", std::nullopt, std::nullopt,
                                            "size of " + g + ": farthest attachment from their centroid", ir::Role::Known);
    for (int j = 0; j < 3; ++j) body.inertia[j] = div(mul(mul(num("2"), sym(m_g)), square(sym(r_g))), num("5"));
  }
  body.position = point_expr(at.centre);
  body.dofs = translations_needed(m, g, in.values);
  const std::string fixed = ground_to_body(d, in, ground, body, at.centred);
  d.add_resonating_body(g);
  d.add_element(spring3(d.names().fresh(g + "_support"), g, fixed, body.position, false, !at.centred,
                        {sym(k_g), sym(k_g), sym(k_g)}, {sym(c_g), sym(c_g), sym(c_g)}));
  return d.finish("ground " + g + " is not rigid: it becomes a body of mass " + m_g + " held to a fixed " + fixed +
                  " by springs of stiffness " + k_g + " and damping " + c_g + " in every direction");
}

// The axes the model's forces act along (a force with an oblique or symbolic direction: all three).
std::array<bool, 3> excited_axes(const ir::ModelIr& m, const ModelValues& values) {
  std::array<bool, 3> axis{false, false, false};
  for (const ir::Input& u : m.inputs) {
    if (u.kind != ir::InputKind::Force) continue;
    if (const std::optional<int> k = axis_of(u.direction, values)) axis[static_cast<std::size_t>(*k)] = true;
    else axis = {true, true, true};
  }
  if (axis == std::array<bool, 3>{false, false, false}) axis = {true, true, true};
  return axis;
}

// The direction away from the structure: from the moving bodies' centre of mass to the attachments' centroid, a
// unit vector with components below 1e-9 set to zero (a base stands below what it carries). Zero when the two
// coincide.
std::array<double, 3> away_from_structure(const OperatorInput& in, const Attachments& at) {
  std::array<double, 3> centre{0, 0, 0};
  double mass = 0;
  for (const ir::Body& b : in.model.bodies) {
    const double m = in.values.of(b.mass);
    for (int k = 0; k < 3; ++k) centre[k] += m * in.values.of(b.position[k]);
    mass += m;
  }
  std::array<double, 3> n{0, 0, 0};
  if (!(mass > 0)) return n;
  for (int k = 0; k < 3; ++k) n[k] = at.centre[k] - centre[k] / mass;
  const double length = std::hypot(n[0], n[1], n[2]);
  if (!(length > 1e-9 * std::max(at.radius, 1e-300))) return {0, 0, 0};
  for (double& v : n) v = std::abs(v / length) < 1e-9 ? 0.0 : v / length;
  return n;
}

// p + factor depth n, written as a person would: components along which n is zero stay plain numbers.
ir::Vec3 offset_point(const std::array<double, 3>& p, const std::array<double, 3>& n, const std::string& depth,
                      double factor = 1) {
  ir::Vec3 out;
  for (int k = 0; k < 3; ++k) {
    if (n[k] == 0) {
      out[k] = number_expr(p[k]);
      continue;
    }
    const double scale = factor * std::abs(n[k]);
    const ir::Expr along = scale == 1 ? sym(depth) : mul(number_expr(scale), sym(depth));
    out[k] = p[k] == 0 ? (n[k] > 0 ? along : neg(along))
                       : (n[k] > 0 ? add(number_expr(p[k]), along) : sub(number_expr(p[k]), along));
  }
  return out;
}

// `simple`: the simple variant of the same ground, whose estimate gives the on-feet base a start of its own
// (Extension::start_from_variant): the same mass, its support stiffness and damping shared among the feet.
Extension on_feet(const OperatorInput& in, const ir::Ground& ground, const Attachments& at, const Extension& simple) {
  Draft d(in, "compliant_ground", ground.name);
  d.set_variant("on feet");
  const Start st = start_values(in);
  const double feet = static_cast<double>(at.distinct.size());
  // The start puts one new mode at the strongest unexplained peak: the base's translation along the excited axes;
  // its other five modes start above it (feet ten times stiffer across, the inertia of a compact block: radius of
  // gyration a third of the attachments' spread). Starting all six at the peak (every axis alike, the gyration
  // radius the full spread) put a rocking mode below the band; from there the local fits escaped by making the
  // base immobile (mass at its bound) and the variant was screened out though its global optimum fitted the
  // spindle's base-on-feet data twice as well as the simple variant (delta BIC -13300 against -5300).
  const double k_foot = st.mass * st.omega * st.omega / feet;
  const std::array<bool, 3> excited = excited_axes(in.model, in.values);
  const std::string& g = ground.name;
  const std::string m_g =
      d.add_parameter("m_" + g, st.mass, "kg", 1e-3 * st.total, 1e3 * st.total, "mass of " + g + " when it moves");
  // A real base is a block below what it carries: the structure's attachments on its top face, its feet at its
  // bottom, its centre of mass halfway between (along `down`, away from the structure). Both depths matter to what
  // the structure feels: the centre of mass below the attachments couples the base's translation and rocking
  // through its inertia, the feet below it through their stiffness. One depth `d_G` places both (feet at 2 d_G):
  // with the two depths estimated apart, the data of a 42 kg box on feet determined neither (std 66 %). Starts as a
  // compact block, the centre of mass half the attachments' spread below them.
  const std::array<double, 3> down = away_from_structure(in, at);
  const bool has_depth = down != std::array<double, 3>{0, 0, 0};
  std::string d_g;
  if (has_depth)
    d_g = d.add_parameter("d_" + g, at.radius / 2, "m", 0.0, 10 * at.radius,
                          "depth of the centre of mass of " + g + " below the points where the model meets it (its "
                          "feet stand at twice that depth)");
  // One radius of gyration per axis, estimated where the model's forces turn the base about that axis (a force
  // along one axis turns about the other two); about an axis no force turns it, the data cannot see the inertia,
  // and it is known (the same compact block's).
  std::array<std::string, 3> r_g;
  for (std::size_t a = 0; a < 3; ++a) {
    bool turned = false;
    for (std::size_t f = 0; f < 3; ++f) turned = turned || (excited[f] && f != a);
    const std::string axis(1, "xyz"[a]);
    r_g[a] = d.add_parameter("r_" + g + axis, at.radius / 3, "m", 1e-2 * at.radius, 1e2 * at.radius,
                             "radius of gyration of " + g + " about " + axis + " (its inertia is m r^2)",
                             turned ? ir::Role::Estimate : ir::Role::Known);
  }
  // The simple variant's new parameters, in the order it declares them: mass, stiffness, damping.
  const std::vector<NewParameter>& sp = simple.new_parameters;
  if (sp.size() != 3) throw std::logic_error("compliant_ground: the simple variant has not 3 new parameters");
  Extension::VariantStart from_simple{simple.variant, {{m_g, {sp[0].name, 1.0}}}};
  std::vector<ir::Expr> k, c;
  std::string k_names, c_names;
  for (std::size_t a = 0; a < 3; ++a) {
    const std::string axis(1, "xyz"[a]);
    const double k_axis = excited[a] ? k_foot : 10 * k_foot;
    const std::string kn = d.add_parameter("k_" + g + axis, k_axis, "N/m", 0.0, std::nullopt,
                                           std::string("stiffness of each foot of ") + g + " along " + axis);
    // Bounded at twice critical damping of the start (100 times the start): unbounded, a damping the data see
    // little of ran to 1e15 N s/m, which locks the base by damping and leaves its dynamic stiffness numerically
    // singular.
    const double c_start = light_damping(k_axis, st.mass / feet);
    const std::string cn = d.add_parameter("c_" + g + axis, c_start, "N s/m", 0.0, 100 * c_start,
                                           std::string("damping of each foot of ") + g + " along " + axis);
    from_simple.from[kn] = {sp[1].name, (excited[a] ? 1 : 10) / feet};
    from_simple.from[cn] = {sp[2].name, 1 / feet};
    k.push_back(sym(kn));
    c.push_back(sym(cn));
    k_names += (k_names.empty() ? "" : ", ") + kn;
    c_names += (c_names.empty() ? "" : ", ") + cn;
  }

  ir::Body body;
  body.name = g;
  body.mass = sym(m_g);
  for (std::size_t j = 0; j < 3; ++j) body.inertia[j] = mul(sym(m_g), square(sym(r_g[j])));
  body.position = has_depth ? offset_point(at.centre, down, d_g) : point_expr(at.centre);
  body.dofs = {ir::Dof::X, ir::Dof::Y, ir::Dof::Z, ir::Dof::RX, ir::Dof::RY, ir::Dof::RZ};
  // With the centre of mass below the attachments, an attachment without a point would follow it: every
  // attachment gets its point written.
  const std::string fixed = ground_to_body(d, in, ground, body, at.centred && !has_depth);
  d.add_resonating_body(g);
  for (std::size_t i = 0; i < at.distinct.size(); ++i)
    d.add_element(spring3(d.names().fresh(g + "_foot" + std::to_string(i + 1)), g, fixed,
                          has_depth ? offset_point(at.distinct[i], down, d_g, 2) : point_expr(at.distinct[i]), true, true,
                          k, c));
  const std::string where = has_depth ? " (its centre of mass " + d_g + " below the points where the model's elements "
                                        "meet it)"
                                      : "";
  const std::string feet_where = has_depth ? "2*" + d_g + " below those points" : "where the model's elements meet it";
  d.set_start_from_variant(std::move(from_simple));
  return d.finish("ground " + g + " is a rigid body of mass " + m_g + where + " standing on " +
                  std::to_string(at.distinct.size()) + " feet " + feet_where + ", each with stiffnesses " + k_names +
                  " and dampings " + c_names + " along x, y, z: it translates and rocks");
}

}  // namespace

std::vector<Extension> compliant_ground(const OperatorInput& in) {
  std::vector<Extension> out;
  for (const ir::Ground& g : in.model.grounds) {
    const bool held = std::any_of(in.model.elements.begin(), in.model.elements.end(), [&](const ir::Element& e) {
      return e.kind != ir::ElementKind::Torsion && (e.a.frame == g.name || e.b.frame == g.name);
    });
    if (!held) continue;
    const Attachments at = attachments_of(in, g.name);
    const bool feet = at.distinct.size() >= 3 && spans_a_plane(at.distinct);
    out.push_back(simple(in, g, at, feet));
    if (feet) out.push_back(on_feet(in, g, at, out.back()));
  }
  return out;
}

}  // namespace mbgen::diagnosis
