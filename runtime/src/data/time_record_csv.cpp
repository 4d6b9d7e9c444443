// Reading CSV time records: the table, then the time column's checks and the channel names.
#include <cmath>
#include <fstream>
#include <iostream>

#include "csv_table.hpp"
#include "mbgen/data/csv.hpp"
#include "mbgen/data/data_error.hpp"

namespace mbgen {

using namespace data_detail;

namespace {

void check_time_grid(const CsvTable& table) {
  const auto& t = table.columns[0];
  const auto& lines = table.row_lines;
  if (t.size() < 2) throw DataError(table.file, lines[0], 1, "a time record needs at least 2 samples");
  for (std::size_t k = 1; k < t.size(); ++k)
    if (!(t[k] > t[k - 1]))
      throw DataError(table.file, lines[k], 1,
                      "time 't' is not strictly increasing: " + format_double(t[k]) + " after " +
                          format_double(t[k - 1]) + " on line " + std::to_string(lines[k - 1]));
  // Uniform sampling: every time lies on the grid t0 + k dt within a fraction of dt. Comparing with the
  // grid rather than step to step keeps rounding in the written times from adding up, and still catches
  // a dropped sample (a deviation of a whole dt).
  const std::size_t n = t.size();
  const double dt = (t[n - 1] - t[0]) / static_cast<double>(n - 1);
  for (std::size_t k = 0; k < n; ++k) {
    const double grid = t[0] + static_cast<double>(k) * dt;
    if (std::abs(t[k] - grid) > kTimeGridTolerance * dt)
      throw DataError(table.file, lines[k], 1,
                      "time 't' is not uniformly sampled: t = " + format_double(t[k]) + " is " +
                          format_double(std::abs(t[k] - grid) / dt) +
                          " sample intervals off the grid t0 + k*dt (dt = " + format_double(dt) +
                          "; tolerance " + format_double(kTimeGridTolerance) + ")");
  }
}

}  // namespace

TimeRecord read_time_record_csv(std::istream& in, const std::string& file_name,
                                const std::optional<ChannelNames>& known) {
  CsvTable table = read_csv_table(in, file_name);
  if (table.header[0] != "t")
    throw DataError(file_name, table.header_line, 1,
                    "the first column of a time record must be 't' (seconds), found '" + table.header[0] + "'" +
                        (table.header[0] == "f_hz" ? " (this is an FRF file)" : ""));
  if (table.header.size() < 2) throw DataError(file_name, table.header_line, 0, "no signal columns after 't'");
  for (std::size_t c = 1; c < table.header.size(); ++c) {
    const std::string& name = table.header[c];
    if (known && !known->is_input(name) && !known->is_output(name))
      throw DataError(file_name, table.header_line, static_cast<int>(c) + 1,
                      "column '" + name + "' is neither a model input nor output (" + known->describe() + ")");
  }
  check_time_grid(table);

  TimeRecord record;
  record.file = file_name;
  record.set = std::move(table.config.set);
  record.hold = table.config.hold.value_or(HoldMode::ZeroOrder);
  // Each column is copied into its vector and released at once, so that a long record is held about once, not
  // twice (docs/limits.md, "Memory of a time record").
  auto take = [&](std::size_t c) {
    const Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(table.columns[c].data(),
                                                                static_cast<Eigen::Index>(table.columns[c].size()));
    std::vector<double>().swap(table.columns[c]);
    return v;
  };
  std::vector<int>().swap(table.row_lines);
  record.t = take(0);
  for (std::size_t c = 1; c < table.header.size(); ++c) record.signals.push_back(Signal{table.header[c], take(c)});
  return record;
}

TimeRecord read_time_record_csv(const std::string& path, const std::optional<ChannelNames>& known) {
  if (path == "-") return read_time_record_csv(std::cin, path, known);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path, 0, 0, "cannot open file");
  return read_time_record_csv(in, path, known);
}

}  // namespace mbgen
