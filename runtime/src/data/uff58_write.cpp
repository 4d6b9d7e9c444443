// Writing dataset 58 in ASCII (runtime/include/mbgen/data/uff.hpp, docs/data.md): the fixed columns of the UFF
// specification, which other readers (pyuff, commercial analysers) parse by column.
#include <cmath>
#include <cstdlib>
#include <ostream>
#include <stdexcept>
#include <string>

#include "mbgen/data/uff.hpp"
#include "uff_fields.hpp"

namespace mbgen {

namespace {

using namespace uff_detail;

// Record 8 to 11: specific data type, length, force and temperature unit exponents, label and units.
std::string axis_line(int type, const std::string& label, const std::string& units) {
  return integer(type, 10) + integer(0, 5) + integer(0, 5) + integer(0, 5) + " " + text_field(label, 20) + " " +
         text_field(units, 20) + "\n";
}

}  // namespace

bool uff58_even_increment_exact(double increment) {
  // Record 7 holds the increment in E13.5: six significant digits. An increment they do not hold exactly would move
  // the far lines (x_k = min + k increment) by k times the rounding.
  const double written = std::strtod(format("%13.5E", increment).c_str(), nullptr);
  return std::abs(written - increment) <= 1e-12 * std::abs(increment);
}

void write_uff58(std::ostream& out, const Uff58Record& r) {
  if (r.binary) throw std::invalid_argument("write_uff58: writes ASCII (58), not binary (58b)");
  if (r.ordinate_data_type != 4 && r.ordinate_data_type != 6)
    throw std::invalid_argument("write_uff58: writes real (4) or complex (6) double ordinates");
  if (r.x.size() != r.y.size() || r.y.size() == 0)
    throw std::invalid_argument("write_uff58: the abscissa and ordinate need the same, non-zero number of points");
  const bool even = r.even_spacing;
  out << "    -1\n";
  out << text_field("    58", 80) << "\n";
  for (const std::string& id : r.id) out << text_field(id, 80) << "\n";
  out << integer(r.function_type, 5) << integer(0, 10) << integer(0, 5) << integer(0, 10) << " "
      << text_field(r.response_entity, 10) << integer(r.response_node, 10) << integer(r.response_direction, 4) << " "
      << text_field(r.reference_entity, 10) << integer(r.reference_node, 10) << integer(r.reference_direction, 4)
      << "\n";
  out << integer(r.ordinate_data_type, 10) << integer(static_cast<long>(r.y.size()), 10) << integer(even ? 1 : 0, 10)
      << format("%13.5E", even ? r.abscissa_min : 0.0) << format("%13.5E", even ? r.abscissa_increment : 0.0)
      << format("%13.5E", r.z_value) << "\n";
  out << axis_line(r.abscissa_type, r.abscissa_label, r.abscissa_units);
  out << axis_line(r.ordinate_type, r.ordinate_label, r.ordinate_units);
  out << axis_line(r.ordinate_denominator_type, r.ordinate_denominator_label, r.ordinate_denominator_units);
  out << axis_line(0, "NONE", "NONE");
  // Data: 4E20.12 a line (two complex points, or four real values); uneven: the abscissa before each point.
  int on_line = 0;
  const auto put = [&](double v) {
    out << format("%20.12E", v);
    if (++on_line == 4) {
      out << "\n";
      on_line = 0;
    }
  };
  for (Eigen::Index k = 0; k < r.y.size(); ++k) {
    if (!even) put(r.x[k]);
    put(r.y[k].real());
    if (r.is_complex()) put(r.y[k].imag());
  }
  if (on_line != 0) out << "\n";
  out << "    -1\n";
}

}  // namespace mbgen
