// Universal File Format dataset 58 (ASCII) and 58b (binary): functions at nodal degrees of freedom, i.e.
// measured time histories and FRFs. Details, and how nodes/directions map to model channels: docs/data.md.
#pragma once

#include <Eigen/Core>

#include <array>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mbgen/data/data_settings.hpp"
#include "mbgen/data/frf_data.hpp"
#include "mbgen/data/time_record.hpp"

namespace mbgen {

struct DataSet;  // mbgen/data/data_set.hpp

// One dataset 58 or 58b as written in the file.
struct Uff58Record {
  int line = 0;                       // line of the dataset number ("58" / "58b"), for messages
  bool binary = false;                // 58b
  std::array<std::string, 5> id;      // ID lines 1..5, trimmed; bytes kept as they are (may be non-ASCII)
  int function_type = 0;              // record 6 field 1: 1 time response, 4 FRF, 6 coherence, ...
  std::string response_entity;        // record 6: entity name, node, direction (1..6 = +X..+RZ, negative,
  int response_node = 0;              //           0 = scalar)
  int response_direction = 0;
  std::string reference_entity;
  int reference_node = 0;
  int reference_direction = 0;
  int ordinate_data_type = 0;         // record 7: 2 real single, 4 real double, 5 complex single, 6 complex double
  Eigen::Index points = 0;            // record 7: number of points
  bool even_spacing = true;           // record 7: abscissa spacing 1 (even) or 0 (uneven)
  double abscissa_min = 0, abscissa_increment = 0, z_value = 0;
  int abscissa_type = 0;              // record 8 specific data type: 17 time, 18 frequency, ...
  std::string abscissa_label, abscissa_units;
  int ordinate_type = 0;              // record 9 specific data type: 8 displacement, 11 velocity, 12 acceleration...
  std::string ordinate_label, ordinate_units;
  int ordinate_denominator_type = 0;  // record 10 specific data type (13: force, an FRF's denominator)
  std::string ordinate_denominator_label, ordinate_denominator_units;
  Eigen::VectorXd x;                  // abscissa of every point (filled in from min/increment when even)
  Eigen::VectorXcd y;                 // ordinate of every point; imaginary part 0 for real data

  bool is_complex() const { return ordinate_data_type == 5 || ordinate_data_type == 6; }
};

// Writes `record` as an ASCII dataset 58 between `-1` delimiter lines, in the specification's fixed columns:
// record 7's E13.5 fields, the data 4E20.12 a line (13 significant digits). Real (4) or complex (6) double ordinates;
// evenly spaced data (even_spacing: abscissa_min and abscissa_increment) or uneven (each point's x written before it).
// Throws std::invalid_argument for 58b, other ordinate types, or x and y of different or zero length.
void write_uff58(std::ostream& out, const Uff58Record& record);
// Whether an even spacing's increment survives record 7's six significant digits exactly (otherwise the far lines
// would move by their index times the rounding: write the abscissa with each point instead).
bool uff58_even_increment_exact(double increment);

// Reads every dataset 58/58b of a UFF file; other datasets (ASCII ones such as 151, 164, 15) are skipped.
// Throws DataError naming file and line for: a file that is not UFF, a header that cannot be parsed, an
// unsupported ordinate type or floating-point format, and data that are cut off or too long (the count
// declared in record 7 is checked). Binary data may be little or big endian, IEEE 754.
std::vector<Uff58Record> read_uff58(std::istream& in, const std::string& file_name);
std::vector<Uff58Record> read_uff58(const std::string& path);

// "+X", "+Y", "+Z", "+RX", "+RY", "+RZ", their negatives, or "S" (scalar, direction 0). Throws DataError for
// other codes.
std::string uff_direction_name(int direction);
// "NODE:DIR", e.g. "12:+Z", "0:S": the key of a measurement point in a UffMapping.
std::string uff_point_key(int node, int direction);

// How UFF measurement points become model channel names, with the settings a UFF file cannot carry.
struct UffMapping {
  std::map<std::string, std::string> names;  // uff_point_key -> model input or output name
  SetMap set;                                 // per-data-set parameter values
  std::optional<HoldMode> hold;               // for time histories
};

// A mapping file: one entry a line, `#` comments:
//     1:+X = xs_front          (point -> model channel)
//     set n_sp=300             (as `# set` in CSV files)
//     hold=none
UffMapping read_uff_mapping(std::istream& in, const std::string& file_name);
UffMapping read_uff_mapping(const std::string& path);

// The mapped name of a point, or "node<NODE>:<DIR>" (e.g. "node1:+X") when the mapping has none.
std::string uff_channel_name(const UffMapping& mapping, int node, int direction);

// Turns the records of one file into one data set:
// - FRFs (function type 4, complex) become an FrfData: output = response point, input = reference point.
//   Coherence records (type 6) whose response/reference match an FRF become its coherence. All records must
//   share the same frequencies.
// - Time responses (type 1, real, even spacing) become a TimeRecord with one signal per response point; all
//   must share the time axis.
// Mixed kinds, other function types, and (with `known`) names that are not model channels are DataErrors.
// (Callers include mbgen/data/data_set.hpp for the result's type.)
DataSet uff_to_data_set(const std::vector<Uff58Record>& records, const std::string& file_name,
                        const UffMapping& mapping, const std::optional<ChannelNames>& known = std::nullopt);

}  // namespace mbgen
