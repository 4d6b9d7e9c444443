#include "diagnosis/operators/operator_support.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "diagnosis/expr_build.hpp"
#include "frontend/model_writer.hpp"

namespace mbgen::diagnosis {

Draft::Draft(const OperatorInput& in, const std::string& operator_name, const std::string& target)
    : names_(in.model), patch_(in.text, in.model.file) {
  ext_.id = operator_name + ":" + target;
  ext_.operator_name = operator_name;
  ext_.target = target;
  ext_.model = in.model;
}

std::string Draft::add_parameter(const std::string& base, double value, const std::string& unit,
                                 std::optional<double> lower, std::optional<double> upper, const std::string& why,
                                 ir::Role role) {
  if (!std::isfinite(value) || (lower && !std::isfinite(*lower)) || (upper && !std::isfinite(*upper)))
    throw UnusableStart(ext_.id + ": the start value or a bound of its parameter " + base +
                        " is not finite at the current estimate");
  ir::Parameter p;
  p.name = names_.fresh(base);
  p.value = number_expr(value);
  p.unit = unit;
  p.role = role;
  if (lower) p.lower = number_expr(*lower);
  if (upper) p.upper = number_expr(*upper);
  add_parameter(p, why);
  return p.name;
}

void Draft::add_parameter(ir::Parameter p, const std::string& why) {
  // The text says why; the model does not keep it, exactly as the parser (which drops comments) would read it.
  p.comment = why;
  declarations_ += frontend::write_parameter(p);
  p.comment.clear();
  if (p.role == ir::Role::Estimate) ext_.new_parameters.push_back({p.name, why});
  ext_.model.parameters.push_back(std::move(p));
}

void Draft::add_ground(ir::Ground g) {
  statements_ += "\n" + frontend::write_ground(g);
  ext_.model.grounds.push_back(std::move(g));
}

void Draft::add_body(ir::Body b) {
  statements_ += "\n" + frontend::write_body(b);
  ext_.model.bodies.push_back(std::move(b));
}

void Draft::add_element(ir::Element e) {
  statements_ += "\n" + frontend::write_element(e);
  ext_.model.elements.push_back(std::move(e));
}

void Draft::add_spin(ir::Spin s) {
  statements_ += frontend::write_spin(s);
  ext_.model.spins.push_back(std::move(s));
}

void Draft::add_filter(ir::Filter f) {
  statements_ += frontend::write_filter(f);
  ext_.model.filters.push_back(std::move(f));
}

namespace {

// The point an attachment without `at` means: its body's centre of mass, a ground's origin.
ir::Vec3 implicit_point(const ir::ModelIr& m, const std::string& frame) {
  for (const ir::Body& b : m.bodies)
    if (b.name == frame) return b.position;
  return {ir::Expr::number("0"), ir::Expr::number("0"), ir::Expr::number("0")};
}

// The text writes an attachment's point only where `has_point` is set: one that is not set must be the implicit
// point, or the candidate's text (what is written, and what later rounds extend) describes another model than the
// one fitted. A base on feet once kept its feet at its bottom in the model and at its centre of mass in the text.
void check_points_written(const ir::ModelIr& m) {
  const ModelValues values(m, {});
  for (const ir::Element& e : m.elements)
    for (const ir::Attachment* a : {&e.a, &e.b}) {
      if (a->has_point || e.kind == ir::ElementKind::Torsion) continue;  // a torsion's points have no meaning
      const ir::Vec3 implicit = implicit_point(m, a->frame);
      for (int k = 0; k < 3; ++k) {
        const double here = values.of(a->point[k]), there = values.of(implicit[k]);
        if (std::abs(here - there) > 1e-12 * (1 + std::abs(there)))
          throw std::logic_error("diagnosis: element " + e.name + "'s point on " + a->frame +
                                 " is not its implicit point but is not written");
      }
    }
}

}  // namespace

Extension Draft::finish(const std::string& description) {
  check_points_written(ext_.model);
  ext_.description = description;
  patch_.append(declarations_ + statements_);
  ext_.mdl_text = patch_.result(ext_.id + ": " + description);
  return std::move(ext_);
}

std::optional<SignalPoint> signal_point(const ir::ModelIr& model, const std::string& body) {
  for (const ir::Input& in : model.inputs)
    if (in.at.frame == body) return SignalPoint{in.name, true, &in.at, &in.direction};
  for (const ir::Output& out : model.outputs)
    if (out.at.frame == body) return SignalPoint{out.name, false, &out.at, &out.direction};
  return std::nullopt;
}

std::optional<int> axis_of(const ir::Direction& d, const ModelValues& values) {
  if (d.axis == "x") return 0;
  if (d.axis == "y") return 1;
  if (d.axis == "z") return 2;
  int nonzero = -1;
  for (int k = 0; k < 3; ++k) {
    if (values.of(d.vector[k]) == 0.0) continue;
    if (nonzero >= 0) return std::nullopt;
    nonzero = k;
  }
  if (nonzero < 0) return std::nullopt;
  return nonzero;
}

bool has_dof(const ir::Body& b, ir::Dof d) { return std::find(b.dofs.begin(), b.dofs.end(), d) != b.dofs.end(); }

double total_moving_mass(const ir::ModelIr& model, const ModelValues& values) {
  double m = 0;
  for (const ir::Body& b : model.bodies) m += values.of(b.mass);
  return m;
}

double largest_translational_stiffness(const ir::ModelIr& model, const ModelValues& values) {
  double k = 0;
  for (const ir::Element& e : model.elements) {
    if (e.kind == ir::ElementKind::Torsion) continue;
    for (const ir::Expr& s : e.stiffness) k = std::max(k, values.of(s));
  }
  return k;
}

double smallest_body_mass(const ir::ModelIr& model, const ModelValues& values) {
  double m = INFINITY;
  for (const ir::Body& b : model.bodies) m = std::min(m, values.of(b.mass));
  return m;
}

std::string add_body_on_axial_spring(Draft& d, const std::string& name, const std::string& mass, const ir::Vec3& point,
                                     int axis, const std::string& frame, const std::string& suffix,
                                     const std::string& stiffness, const std::string& damping) {
  ir::Body body;
  body.name = d.names().fresh(name);
  body.mass = sym(mass);
  body.position = point;
  body.dofs = {static_cast<ir::Dof>(axis)};
  d.add_body(body);

  ir::Element spring;
  spring.kind = ir::ElementKind::Spring;
  spring.name = d.names().fresh(body.name + suffix);
  spring.a.frame = frame;
  spring.a.point = point;
  spring.a.has_point = true;
  spring.b.frame = body.name;
  spring.b.point = point;
  spring.direction.axis = std::string(1, "xyz"[axis]);
  for (int j = 0; j < 3; ++j) spring.direction.vector[j] = num(j == axis ? "1" : "0");
  spring.stiffness = {sym(stiffness)};
  spring.damping = {sym(damping)};
  d.add_element(spring);
  return body.name;
}

double light_damping(double k, double m) { return 2 * 0.02 * std::sqrt(std::max(k, 0.0) * std::max(m, 0.0)); }

}  // namespace mbgen::diagnosis
