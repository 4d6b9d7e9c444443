#include "emit/inspect_common.hpp"

#include <cstdio>
#include <stdexcept>

#include <Eigen/Core>
#include <mbgen/dynamics/dynamics_error.hpp>

#include "emit/inspect.hpp"
#include "frontend/diagnostics.hpp"

namespace mbgen::emit {

namespace detail {

InspectNames inspect_names(const symbolic::SymbolicModel& sm) {
  InspectNames n;
  for (const auto& c : sm.coordinates) n.coordinates.push_back(c.name());
  if (sm.model) {
    for (const auto& in : sm.model->inputs) n.inputs.push_back(in.name);
    for (const auto& out : sm.model->outputs) n.outputs.push_back(out.name);
  } else {
    for (unsigned j = 0; j < sm.B.cols(); ++j) n.inputs.push_back("u" + std::to_string(j));
    for (unsigned i = 0; i < sm.Cd.rows(); ++i) n.outputs.push_back("y" + std::to_string(i));
  }
  return n;
}

double value_as_double(const GiNaC::ex& e) {
  const GiNaC::ex v = GiNaC::evalf(e);
  if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
    throw std::invalid_argument("inspect: expression has no real value at the current parameter values");
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

const char* role_name(const symbolic::FreeParameter& p) {
  if (!p.ir) return "known";
  switch (p.ir->role) {
    case ir::Role::Known: return "known";
    case ir::Role::Estimate: return "estimate";
    case ir::Role::Fixed: return "fixed";
  }
  return "known";
}

std::string unit_of(const symbolic::FreeParameter& p) { return p.ir ? p.ir->unit : std::string(); }

std::vector<Mode> modes_at_current_values(const symbolic::SymbolicModel& sm) {
  const GiNaC::exmap values = sm.values();
  auto numeric = [&](const GiNaC::matrix& m) {
    Eigen::MatrixXd out(m.rows(), m.cols());
    for (unsigned r = 0; r < m.rows(); ++r)
      for (unsigned c = 0; c < m.cols(); ++c) out(r, c) = value_as_double(m(r, c).subs(values));
    return out;
  };
  try {
    return modal_analysis(numeric(sm.M), numeric(sm.C_total), numeric(sm.K));
  } catch (const DynamicsError& e) {  // the model's values, not a bug: name the model
    throw frontend::ModelError(sm.model ? sm.model->file : "", {},
                               std::string("cannot compute the modes at the current parameter values: ") + e.what());
  }
}

bool has_spin(const symbolic::SymbolicModel& sm) {
  for (unsigned r = 0; r < sm.G.rows(); ++r)
    for (unsigned c = 0; c < sm.G.cols(); ++c)
      if (!sm.G(r, c).is_zero()) return true;
  return false;
}

std::string short_number(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

}  // namespace detail

InspectFormat parse_inspect_format(const std::string& name) {
  if (name == "markdown") return InspectFormat::Markdown;
  if (name == "latex") return InspectFormat::Latex;
  if (name == "json") return InspectFormat::Json;
  throw std::invalid_argument("unknown inspect format '" + name + "' (expected markdown, latex or json)");
}

std::string emit_inspect(const symbolic::SymbolicModel& sm, InspectFormat format) {
  switch (format) {
    case InspectFormat::Markdown: return emit_inspect_markdown(sm);
    case InspectFormat::Latex: return emit_inspect_latex(sm);
    case InspectFormat::Json: return emit_inspect_json(sm);
  }
  throw std::invalid_argument("unknown inspect format");
}

}  // namespace mbgen::emit
