#include "frontend/model_writer.hpp"

#include <algorithm>

namespace mbgen::frontend {

namespace {

std::string padded(std::string s, std::size_t width) {
  if (s.size() < width) s.append(width - s.size(), ' ');
  return s;
}

std::string join(const std::vector<ir::Expr>& values) {
  std::string out;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) out += ", ";
    out += ir::to_string(values[i]);
  }
  return out;
}

// Column widths that line up a block of parameter declarations (0 = no alignment).
struct ParamColumns {
  std::size_t name = 0, value = 0, unit = 0, role = 0;
};

std::string unit_text(const ir::Parameter& p) { return p.unit.empty() ? "" : "\"" + p.unit + "\""; }

// The role is written unless it is the default (`known`): the examples read that way.
std::string role_text(const ir::Parameter& p) { return p.role == ir::Role::Known ? "" : ir::to_string(p.role); }

std::string bounds_text(const ir::Parameter& p) {
  if (!p.lower && !p.upper) return "";
  return "in [" + (p.lower ? ir::to_string(*p.lower) : std::string("-inf")) + ", " +
         (p.upper ? ir::to_string(*p.upper) : std::string("inf")) + "]";
}

std::string parameter_line(const ir::Parameter& p, const ParamColumns& w) {
  // Fields are padded only when something follows them, so lines carry no trailing blanks.
  std::vector<std::string> fields = {"param " + padded(p.name, w.name) + " = " + ir::to_string(p.value),
                                     unit_text(p), role_text(p), bounds_text(p)};
  const std::size_t widths[] = {w.name + 9 + w.value, w.unit, w.role, 0};
  std::size_t last = 0;
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (!fields[i].empty()) last = i;
  std::string line;
  for (std::size_t i = 0; i <= last; ++i) {
    if (i) line += "  ";
    line += i < last ? padded(fields[i], widths[i]) : fields[i];
  }
  if (!p.comment.empty()) line += "  # " + p.comment;
  return line + "\n";
}

bool all_zero_literals(const ir::Vec3& v) {
  return std::all_of(v.begin(), v.end(),
                     [](const ir::Expr& e) { return e.is_number() && ir::is_zero_literal(e.text); });
}

}  // namespace

std::string write_vec3(const ir::Vec3& v) {
  return "(" + ir::to_string(v[0]) + ", " + ir::to_string(v[1]) + ", " + ir::to_string(v[2]) + ")";
}

std::string write_direction(const ir::Direction& d) { return d.axis.empty() ? write_vec3(d.vector) : d.axis; }

std::string write_attachment(const ir::Attachment& a) {
  return a.has_point ? a.frame + " at " + write_vec3(a.point) : a.frame;
}

std::string write_parameter(const ir::Parameter& p) { return parameter_line(p, {}); }

std::string write_ground(const ir::Ground& g) { return "ground " + g.name + "\n"; }

std::string write_body(const ir::Body& b) {
  std::string out = "body " + b.name + " {\n  mass " + ir::to_string(b.mass) + "\n";
  const bool any_inertia = std::any_of(b.inertia.begin(), b.inertia.end(), [](const auto& j) { return j.has_value(); });
  if (any_inertia) {
    const bool products = b.inertia[3] || b.inertia[4] || b.inertia[5];
    out += "  inertia ";
    for (int k = 0; k < (products ? 6 : 3); ++k) {
      if (k) out += ", ";
      out += b.inertia[k] ? ir::to_string(*b.inertia[k]) : "0";
    }
    out += "\n";
  }
  // The default centre of mass is the origin; writing `at (0, 0, 0)` would say nothing new.
  if (!all_zero_literals(b.position)) out += "  at " + write_vec3(b.position) + "\n";
  out += "  dof";
  for (ir::Dof d : b.dofs) out += std::string(" ") + ir::to_string(d);
  return out + "\n}\n";
}

std::string write_element(const ir::Element& e) {
  std::string out = std::string(ir::to_string(e.kind)) + " " + e.name + " {\n";
  out += "  from " + write_attachment(e.a) + "\n";
  out += "  to " + write_attachment(e.b) + "\n";
  if (e.kind == ir::ElementKind::Spring) out += "  along " + write_direction(e.direction) + "\n";
  if (e.kind == ir::ElementKind::Torsion) out += "  about " + write_direction(e.direction) + "\n";
  out += "  stiffness " + join(e.stiffness) + "\n";
  if (!e.damping.empty()) out += "  damping " + join(e.damping) + "\n";
  return out + "}\n";
}

std::string write_spin(const ir::Spin& s) {
  return "spin " + s.body + " about " + s.axis + " speed " + ir::to_string(s.speed) + "\n";
}

std::string write_input(const ir::Input& in) {
  // A moment acts on the whole frame: its point is not written (the parser rejects one).
  const std::string on = in.kind == ir::InputKind::Moment ? in.at.frame : write_attachment(in.at);
  return "input " + in.name + " " + ir::to_string(in.kind) + " on " + on + " along " + write_direction(in.direction) +
         (in.gain ? " gain " + ir::to_string(*in.gain) : "") + "\n";
}

std::string write_output(const ir::Output& out) {
  return "output " + out.name + " " + ir::to_string(out.kind) + " of " + write_attachment(out.at) + " along " +
         write_direction(out.direction) + "\n";
}

std::string write_filter(const ir::Filter& f) {
  std::string out = "filter " + f.name + " on " + f.output + " " + ir::to_string(f.kind);
  if (f.cutoff) out += " cutoff " + ir::to_string(*f.cutoff);
  if (f.damping) out += " damping " + ir::to_string(*f.damping);
  if (f.time) out += " time " + ir::to_string(*f.time);
  if (f.factor) out += " factor " + ir::to_string(*f.factor);
  if (f.kind == ir::FilterKind::Delay && f.sections != 1) out += " sections " + std::to_string(f.sections);
  return out + "\n";
}

std::string write_model(const ir::ModelIr& model) {
  std::string out = "model " + model.name + "\n";

  if (!model.parameters.empty()) {
    ParamColumns w;
    for (const ir::Parameter& p : model.parameters) {
      w.name = std::max(w.name, p.name.size());
      w.value = std::max(w.value, ir::to_string(p.value).size());
      w.unit = std::max(w.unit, unit_text(p).size());
      w.role = std::max(w.role, role_text(p).size());
    }
    out += "\n";
    for (const ir::Parameter& p : model.parameters) out += parameter_line(p, w);
  }
  if (!model.grounds.empty()) {
    out += "\n";
    for (const ir::Ground& g : model.grounds) out += write_ground(g);
  }
  for (const ir::Body& b : model.bodies) out += "\n" + write_body(b);
  for (const ir::Element& e : model.elements) out += "\n" + write_element(e);
  if (!model.spins.empty()) {
    out += "\n";
    for (const ir::Spin& s : model.spins) out += write_spin(s);
  }
  if (!model.inputs.empty() || !model.outputs.empty()) {
    out += "\n";
    for (const ir::Input& in : model.inputs) out += write_input(in);
    for (const ir::Output& o : model.outputs) out += write_output(o);
  }
  if (!model.filters.empty()) {
    out += "\n";
    for (const ir::Filter& f : model.filters) out += write_filter(f);
  }
  return out;
}

}  // namespace mbgen::frontend
