// Universal File Format dataset 55 (data at nodes: here mode shapes, one dataset per mode), dataset 15 (nodes with
// their coordinates, the geometry the shapes are drawn on) and dataset 82 (trace lines between nodes, which a viewer
// draws as the structure), ASCII. What mbgen writes and reads: docs/data.md.
//
// Layout followed (SDRC's dataset descriptions as the ARTeMIS Modal help reproduces them, "UFF Data Set Number 55"
// "Number 15" and "Number 82", and pyuff's dataset_55.py/dataset_15.py/dataset_82.py, which read and write the same
// fields):
//   55 record 1-5   ID lines (40A2)
//      record 6     6I10: model type (1 structural), analysis type (2 normal mode, 3 complex eigenvalue first order,
//                   7 complex eigenvalue second order), data characteristic (1 scalar, 2 three translations,
//                   3 three translations and three rotations), specific data type (8 displacement, 11 velocity,
//                   12 acceleration, ...), data type (2 real, 5 complex), values per node (1, 3 or 6)
//      record 7     8I10: number of integer values (2), number of real values (4 or 6), load case, mode number
//      record 8     6E13.5: normal mode: frequency (Hz), modal mass, viscous damping ratio, hysteretic damping ratio;
//                   complex mode: eigenvalue (re, im; rad/s), modal A (re, im), modal B (re, im)
//      record 9     I10: node number;  record 10  6E13.5: its values (complex: re, im of each), repeated per node
//   15 record 1     4I10,1P3E13.5: node label, definition and displacement coordinate systems, colour, x, y, z
//   82 record 1     3I10: trace line number, number of nodes (entries of record 3, at most 250), colour
//      record 2     80A1: identification line
//      record 3     8I10: the nodes, a line drawn to each from the one before; 0 lifts the pen (a move to the next)
// E13.5 holds six significant digits: that is the precision of everything in these datasets.
#pragma once

#include <Eigen/Core>

#include <array>
#include <complex>
#include <iosfwd>
#include <string>
#include <vector>

namespace mbgen {

// One dataset 55: one mode's shape at the nodes.
struct Uff55Record {
  int line = 0;                     // line of the dataset number ("55") when read, for messages
  std::array<std::string, 5> id;    // ID lines 1..5, trimmed
  int model_type = 1;               // record 6 field 1
  int analysis_type = 3;            // field 2: 2 normal mode, 3 (or 7) complex mode
  int data_characteristic = 2;      // field 3: 1 scalar, 2 three translations, 3 six values
  int specific_data_type = 8;       // field 4: 8 displacement, 11 velocity, 12 acceleration
  bool complex = true;              // field 5: data type 5 (complex) or 2 (real)
  int load_case = 0;                // record 7
  int mode_number = 0;
  // Record 8 of a normal mode (analysis type 2).
  double frequency_hz = 0, modal_mass = 0, viscous_damping = 0, hysteretic_damping = 0;
  // Record 8 of a complex mode (analysis type 3 or 7): the eigenvalue in rad/s, modal A and B (0: not given).
  std::complex<double> eigenvalue, modal_a, modal_b;
  std::vector<int> nodes;           // record 9 of every node, in file order
  Eigen::MatrixXcd values;          // nodes x values per node: X, Y, Z (and RX, RY, RZ); imaginary 0 when real

  int values_per_node() const { return data_characteristic == 1 ? 1 : data_characteristic == 3 ? 6 : 3; }
  // The mode's frequency (Hz) and damping ratio: record 8's for a normal mode, from the eigenvalue for a complex one.
  double f_hz() const;
  double zeta() const;
};

// Writes `record` as an ASCII dataset 55 between `-1` lines in the fixed columns above. Throws std::invalid_argument
// for an analysis type other than 2, 3 or 7, a data characteristic other than 1, 2 or 3, a node count that differs
// from the rows of `values`, or columns that differ from values_per_node().
void write_uff55(std::ostream& out, const Uff55Record& record);

// Every dataset 55 of a UFF file, in file order; other datasets (58, 58b, 15, 151, 164, ...) are skipped. Throws
// DataError naming file and line for: a file that is not UFF, a record 6 to 10 that cannot be read, an analysis
// type that is not a mode (5: frequency response, 1: static, ...), values per node that do not match the data
// characteristic, and a node whose values are cut off; and for a file without a dataset 55.
std::vector<Uff55Record> read_uff55(std::istream& in, const std::string& file_name);
std::vector<Uff55Record> read_uff55(const std::string& path);

// One node of dataset 15.
struct Uff15Node {
  int node = 0;
  int definition_cs = 0, displacement_cs = 0, colour = 0;
  std::array<double, 3> xyz{};
  int line = 0;  // when read
};

// Writes the nodes as one dataset 15 (at least one node; std::invalid_argument otherwise).
void write_uff15(std::ostream& out, const std::vector<Uff15Node>& nodes);
// Every node of the file's datasets 15 (none: an empty list); DataError naming file and line for a malformed one.
std::vector<Uff15Node> read_uff15(std::istream& in, const std::string& file_name);

// One dataset 82: a trace line through nodes.
struct Uff82TraceLine {
  int number = 0;          // record 1 field 1
  int colour = 0;          // field 3
  std::string id;          // record 2, trimmed
  std::vector<int> nodes;  // record 3: node numbers, 0 a pen lift
  int line = 0;            // of the dataset number, when read
};

// Writes one dataset 82. std::invalid_argument for fewer than 2 or more than 250 entries, or a negative one.
void write_uff82(std::ostream& out, const Uff82TraceLine& trace);
// Every dataset 82 of the file, in file order (none: an empty list); record 3 is read to the dataset's end whatever
// record 1's count says (writers count differently). DataError naming file and line for a malformed one (a record 1
// that is not three integers, a node that is not an integer >= 0) or for malformed datasets 55 and 15 in the file.
// read_uff55 and the FRF reader (read_uff58) skip datasets 82.
std::vector<Uff82TraceLine> read_uff82(std::istream& in, const std::string& file_name);

}  // namespace mbgen
