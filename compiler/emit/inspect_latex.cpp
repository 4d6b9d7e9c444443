// LaTeX inspection: a standalone document (amsmath), matrices as bmatrix, expressions by latex_text (infix_printer.hpp).
#include <sstream>

#include "emit/inspect.hpp"
#include "emit/infix_printer.hpp"
#include "emit/inspect_common.hpp"

namespace mbgen::emit {

namespace {

// User text (a unit string, names) as literal LaTeX text: no character of it can start a command.
std::string escape_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '\\') out += "\\textbackslash{}";
    else if (c == '~') out += "\\textasciitilde{}";
    else if (c == '^') out += "\\textasciicircum{}";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) out += ' ';
    else {
      if (c == '_' || c == '%' || c == '&' || c == '#' || c == '$' || c == '{' || c == '}') out += '\\';
      out += c;
    }
  }
  return out;
}

// The model's own symbols are printed (GiNaC's default TeX names): substituting symbols with TeX names would
// create fresh symbols, whose hash-based order in sums differs from run to run.
GiNaC::exmap tex_symbols(const symbolic::SymbolicModel&) { return {}; }

std::string latex(const GiNaC::ex& e) { return latex_text(e); }

void matrix(std::ostringstream& os, const std::string& name, const GiNaC::matrix& m, const GiNaC::exmap& tex) {
  os << "\\[\n" << name << " = \\begin{bmatrix}\n";
  for (unsigned r = 0; r < m.rows(); ++r) {
    os << "  ";
    for (unsigned c = 0; c < m.cols(); ++c) os << (c ? " & " : "") << latex(m(r, c).subs(tex));
    os << (r + 1 < m.rows() ? " \\\\\n" : "\n");
  }
  os << "\\end{bmatrix}\n\\]\n\n";
}

std::string comma_list(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::string("\\texttt{") + escape_text(v[i]) + "}";
  return s.empty() ? "(none)" : s;
}

}  // namespace

std::string emit_inspect_latex(const symbolic::SymbolicModel& sm) {
  const detail::InspectNames n = detail::inspect_names(sm);
  const GiNaC::exmap tex = tex_symbols(sm);
  std::ostringstream os;
  os << "\\documentclass{article}\n\\usepackage{amsmath}\n\\setcounter{MaxMatrixCols}{20}\n\\begin{document}\n\n"
     << "\\section*{Model \\texttt{" << escape_text(sm.model ? sm.model->name : std::string("model")) << "}}\n\n"
     << "$M\\ddot q + C\\dot q + K q = B u$, $y = C_d q + C_v \\dot q + C_a \\ddot q$ ($C$ includes the gyroscopic "
        "matrix $G$).\n\n";
  os << "\\subsection*{Parameters}\n\\begin{tabular}{lllll}\nname & value & exact & role & unit \\\\\n\\hline\n";
  for (const auto& p : sm.parameters)
    os << "$" << latex(p.sym.subs(tex)) << "$ & " << detail::short_number(detail::value_as_double(p.value)) << " & $"
       << latex(p.value) << "$ & " << detail::role_name(p) << " & " << escape_text(detail::unit_of(p)) << " \\\\\n";
  os << "\\end{tabular}\n\n";
  os << "Coordinates: " << comma_list(n.coordinates) << ".\n\nInputs: " << comma_list(n.inputs)
     << ".\n\nOutputs: " << comma_list(n.outputs) << ".\n\n";

  os << "\\subsection*{Equations of motion}\n";
  matrix(os, "M", sm.M, tex);
  matrix(os, "C", sm.C_total, tex);
  if (detail::has_spin(sm)) matrix(os, "G", sm.G, tex);
  matrix(os, "K", sm.K, tex);
  matrix(os, "B", sm.B, tex);
  matrix(os, "C_d", sm.Cd, tex);
  matrix(os, "C_v", sm.Cv, tex);
  matrix(os, "C_a", sm.Ca, tex);

  os << "\\subsection*{Transfer functions}\nCoefficients in ascending powers of $s$; denominators monic.\n\n";
  for (const auto& tf : sm.transfer_functions) {
    os << "\\paragraph{" << "\\texttt{" << escape_text(n.outputs.at(static_cast<std::size_t>(tf.output))) << "} / \\texttt{"
       << escape_text(n.inputs.at(static_cast<std::size_t>(tf.input))) << "}"
       << (tf.symbolic ? ""
           : tf.exact  ? " (exact numbers at the current values)"
                       : " (not expanded: a block of " + std::to_string(tf.coordinates.size()) +
                             " coordinates; computed at run time)")
       << "}\n";
    if (!tf.exact) continue;
    os << "\\begin{align*}\n";
    for (std::size_t k = 0; k < tf.numerator.size(); ++k)
      os << "b_{" << k << "} &= " << latex(tf.numerator[k].subs(tex)) << " \\\\\n";
    for (std::size_t k = 0; k < tf.denominator.size(); ++k)
      os << "a_{" << k << "} &= " << latex(tf.denominator[k].subs(tex))
         << (k + 1 < tf.denominator.size() ? " \\\\\n" : "\n");
    os << "\\end{align*}\n\n";
  }

  os << "\\subsection*{Pole-zero cancellations}\n";
  if (sm.cancellations.empty()) os << "None at the current values.\n\n";
  for (const auto& c : sm.cancellations)
    if (c.common_factor.is_zero())  // probable, not exact (a block too large for exact coefficients)
      os << escape_text(c.text) << "\n\n";
    else
      os << "\\texttt{" << escape_text(n.outputs.at(static_cast<std::size_t>(c.output))) << "} / \\texttt{"
       << escape_text(n.inputs.at(static_cast<std::size_t>(c.input))) << "}: common factor $"
       << latex(c.common_factor) << "$.\n\n";

  os << "\\subsection*{Modes at the current values}\n\\begin{tabular}{rrr}\n\\# & $f$ [Hz] & $\\zeta$ \\\\\n\\hline\n";
  const auto modes = detail::modes_at_current_values(sm);
  for (std::size_t i = 0; i < modes.size(); ++i)
    os << i + 1 << " & " << detail::short_number(modes[i].f_hz) << " & " << detail::short_number(modes[i].zeta)
       << " \\\\\n";
  os << "\\end{tabular}\n\n\\end{document}\n";
  return os.str();
}

}  // namespace mbgen::emit
