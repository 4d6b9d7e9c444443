// Markdown inspection: tables of parameters and modes, matrices as tables of infix expressions.
#include <sstream>

#include <mbgen/report/markdown.hpp>

#include "emit/infix_printer.hpp"
#include "emit/inspect.hpp"
#include "emit/inspect_common.hpp"

namespace mbgen::emit {

namespace {

// `|` would break a table cell; infix text never contains it, names cannot (a unit can: markdown_text).
void matrix_table(std::ostringstream& os, const std::string& title, const GiNaC::matrix& m,
                  const std::vector<std::string>& row_names, const std::vector<std::string>& col_names) {
  os << "### " << title << "\n\n|  |";
  for (const auto& c : col_names) os << " " << c << " |";
  os << "\n|---|";
  for (std::size_t c = 0; c < col_names.size(); ++c) os << "---|";
  os << "\n";
  for (unsigned r = 0; r < m.rows(); ++r) {
    os << "| **" << row_names.at(r) << "** |";
    for (unsigned c = 0; c < m.cols(); ++c) os << " " << (m(r, c).is_zero() ? "0" : "`" + infix_text(m(r, c)) + "`") << " |";
    os << "\n";
  }
  os << "\n";
}

void name_list(std::ostringstream& os, const std::string& title, const std::vector<std::string>& names) {
  os << "## " << title << "\n\n";
  if (names.empty()) os << "(none)\n";
  for (std::size_t i = 0; i < names.size(); ++i) os << i + 1 << ". `" << names[i] << "`\n";
  os << "\n";
}

}  // namespace

std::string emit_inspect_markdown(const symbolic::SymbolicModel& sm) {
  const detail::InspectNames n = detail::inspect_names(sm);
  std::ostringstream os;
  os << "# Model `" << (sm.model ? sm.model->name : std::string("model")) << "`\n\n"
     << "M q'' + C q' + K q = B u,  y = Cd q + Cv q' + Ca q'' (C includes the gyroscopic matrix G).\n\n";

  os << "## Parameters\n\n| name | value | exact | role | unit |\n|---|---|---|---|---|\n";
  for (const auto& p : sm.parameters)
    os << "| `" << p.name << "` | " << detail::short_number(detail::value_as_double(p.value)) << " | `"
       << infix_text(p.value) << "` | " << detail::role_name(p) << " | " << markdown_text(detail::unit_of(p)) << " |\n";
  os << "\n";
  name_list(os, "Coordinates", n.coordinates);
  name_list(os, "Inputs", n.inputs);
  name_list(os, "Outputs", n.outputs);

  os << "## Equations of motion\n\n";
  matrix_table(os, "Mass matrix M", sm.M, n.coordinates, n.coordinates);
  matrix_table(os, "Damping matrix C (with G)", sm.C_total, n.coordinates, n.coordinates);
  if (detail::has_spin(sm)) matrix_table(os, "Gyroscopic matrix G", sm.G, n.coordinates, n.coordinates);
  matrix_table(os, "Stiffness matrix K", sm.K, n.coordinates, n.coordinates);
  matrix_table(os, "Input matrix B", sm.B, n.coordinates, n.inputs);
  matrix_table(os, "Output map Cd (displacements)", sm.Cd, n.outputs, n.coordinates);
  matrix_table(os, "Output map Cv (velocities)", sm.Cv, n.outputs, n.coordinates);
  matrix_table(os, "Output map Ca (accelerations)", sm.Ca, n.outputs, n.coordinates);

  os << "## Transfer functions\n\nCoefficients in ascending powers of s; denominators monic.\n\n";
  for (const auto& tf : sm.transfer_functions) {
    os << "### " << n.outputs.at(static_cast<std::size_t>(tf.output)) << " / "
       << n.inputs.at(static_cast<std::size_t>(tf.input))
       << (tf.symbolic ? " (symbolic)"
           : tf.exact  ? " (exact numbers at the current values)"
                       : " (not expanded: a block of " + std::to_string(tf.coordinates.size()) +
                             " coordinates; the generated code computes the coefficients at run time)")
       << "\n\n";
    for (std::size_t k = 0; k < tf.numerator.size(); ++k)
      os << "- b" << k << " = `" << infix_text(tf.numerator[k]) << "`\n";
    for (std::size_t k = 0; k < tf.denominator.size(); ++k)
      os << "- a" << k << " = `" << infix_text(tf.denominator[k]) << "`\n";
    os << "\n";
  }

  os << "## Pole-zero cancellations\n\n";
  if (sm.cancellations.empty()) os << "None at the current values.\n";
  for (const auto& c : sm.cancellations) {
    if (c.common_factor.is_zero()) {  // probable, not exact (a block too large for exact coefficients)
      os << "- " << c.text << "\n";
      continue;
    }
    os << "- " << n.outputs.at(static_cast<std::size_t>(c.output)) << " / "
       << n.inputs.at(static_cast<std::size_t>(c.input)) << ": common factor `" << infix_text(c.common_factor)
       << "`" << (c.text.empty() ? "" : ". " + c.text) << "\n";
  }
  os << "\n";

  os << "## Modes at the current values\n\n| # | f [Hz] | zeta |\n|---|---|---|\n";
  const auto modes = detail::modes_at_current_values(sm);
  for (std::size_t i = 0; i < modes.size(); ++i)
    os << "| " << i + 1 << " | " << detail::short_number(modes[i].f_hz) << " | " << detail::short_number(modes[i].zeta)
       << " |\n";
  return os.str();
}

}  // namespace mbgen::emit
