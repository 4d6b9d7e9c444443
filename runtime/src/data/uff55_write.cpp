// Writing datasets 55 (mode shapes at nodes), 15 (nodes) and 82 (trace lines) in ASCII, in the fixed columns of the specification
// (runtime/include/mbgen/data/uff55.hpp names the layout and where it comes from).
#include <cmath>
#include <ostream>
#include <stdexcept>
#include <string>

#include "mbgen/data/uff55.hpp"
#include "uff_fields.hpp"
#include "numerics/constants.hpp"

namespace mbgen {

using namespace uff_detail;

double Uff55Record::f_hz() const {
  if (analysis_type == 2) return frequency_hz;
  return std::abs(eigenvalue) / numerics::kTwoPi;
}

double Uff55Record::zeta() const {
  if (analysis_type == 2) return viscous_damping;
  const double magnitude = std::abs(eigenvalue);
  return magnitude > 0 ? -eigenvalue.real() / magnitude : 0.0;
}

namespace {

// Values in 6E13.5, six to a line.
class RealLine {
 public:
  explicit RealLine(std::ostream& out) : out_(out) {}
  void put(double v) {
    out_ << format("%13.5E", v);
    if (++on_line_ == 6) {
      out_ << "\n";
      on_line_ = 0;
    }
  }
  void end() {
    if (on_line_ != 0) out_ << "\n";
    on_line_ = 0;
  }

 private:
  std::ostream& out_;
  int on_line_ = 0;
};

}  // namespace

void write_uff55(std::ostream& out, const Uff55Record& r) {
  const bool normal = r.analysis_type == 2;
  if (!normal && r.analysis_type != 3 && r.analysis_type != 7)
    throw std::invalid_argument("write_uff55: writes modes: analysis type 2 (normal) or 3, 7 (complex)");
  if (r.data_characteristic < 1 || r.data_characteristic > 3)
    throw std::invalid_argument("write_uff55: data characteristic 1 (scalar), 2 (3 DOF) or 3 (6 DOF)");
  if (static_cast<Eigen::Index>(r.nodes.size()) != r.values.rows() || r.values.cols() != r.values_per_node())
    throw std::invalid_argument("write_uff55: one row of values per node, values_per_node() columns");
  out << "    -1\n" << text_field("    55", 80) << "\n";
  for (const std::string& id : r.id) out << text_field(id.empty() ? "NONE" : id, 80) << "\n";
  out << integer(r.model_type, 10) << integer(r.analysis_type, 10) << integer(r.data_characteristic, 10)
      << integer(r.specific_data_type, 10) << integer(r.complex ? 5 : 2, 10) << integer(r.values_per_node(), 10)
      << "\n";
  out << integer(2, 10) << integer(normal ? 4 : 6, 10) << integer(r.load_case, 10) << integer(r.mode_number, 10)
      << "\n";
  RealLine reals(out);
  if (normal) {
    for (const double v : {r.frequency_hz, r.modal_mass, r.viscous_damping, r.hysteretic_damping}) reals.put(v);
  } else {
    for (const std::complex<double> v : {r.eigenvalue, r.modal_a, r.modal_b}) {
      reals.put(v.real());
      reals.put(v.imag());
    }
  }
  reals.end();
  for (std::size_t n = 0; n < r.nodes.size(); ++n) {
    out << integer(r.nodes[n], 10) << "\n";
    for (Eigen::Index c = 0; c < r.values.cols(); ++c) {
      const std::complex<double> v = r.values(static_cast<Eigen::Index>(n), c);
      reals.put(v.real());
      if (r.complex) reals.put(v.imag());
    }
    reals.end();
  }
  out << "    -1\n";
}

void write_uff15(std::ostream& out, const std::vector<Uff15Node>& nodes) {
  if (nodes.empty()) throw std::invalid_argument("write_uff15: no nodes");
  out << "    -1\n" << text_field("    15", 80) << "\n";
  for (const Uff15Node& n : nodes) {
    out << integer(n.node, 10) << integer(n.definition_cs, 10) << integer(n.displacement_cs, 10)
        << integer(n.colour, 10);
    for (const double x : n.xyz) out << format("%13.5E", x);
    out << "\n";
  }
  out << "    -1\n";
}

void write_uff82(std::ostream& out, const Uff82TraceLine& trace) {
  if (trace.nodes.size() < 2 || trace.nodes.size() > 250)
    throw std::invalid_argument("write_uff82: a trace line has 2 to 250 entries");
  for (const int n : trace.nodes)
    if (n < 0) throw std::invalid_argument("write_uff82: a node number is >= 0");
  out << "    -1\n" << text_field("    82", 80) << "\n";
  out << integer(trace.number, 10) << integer(static_cast<long>(trace.nodes.size()), 10) << integer(trace.colour, 10)
      << "\n";
  out << text_field(trace.id.empty() ? "NONE" : trace.id, 80) << "\n";
  for (std::size_t k = 0; k < trace.nodes.size(); ++k)
    out << integer(trace.nodes[k], 10) << (k % 8 == 7 || k + 1 == trace.nodes.size() ? "\n" : "");
  out << "    -1\n";
}

}  // namespace mbgen
