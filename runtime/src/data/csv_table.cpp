#include "csv_table.hpp"

#include <cmath>
#include <map>

#include "mbgen/data/data_error.hpp"

namespace mbgen::data_detail {

namespace {
int column_of(std::size_t index) { return static_cast<int>(index) + 1; }
}  // namespace

CsvTable read_csv_table(std::istream& in, const std::string& file) {
  CsvTable table;
  table.file = file;
  LineReader reader(in, file);
  std::string line;
  bool any_line = false;

  // Preamble: blank lines and `#` comments (some of them configuration), then the header.
  while (reader.next(line)) {
    any_line = true;
    const std::string_view text = trim(line);
    if (text.empty()) continue;
    if (text.front() == '#') {
      parse_config_comment(text.substr(1), file, reader.line_number(), table.config);
      continue;
    }
    table.header_line = reader.line_number();
    std::map<std::string, std::size_t> seen;
    const auto fields = split_fields(text);
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const std::string name(fields[c]);
      if (name.empty())
        throw DataError(file, table.header_line, column_of(c), "empty column name in the header");
      if (seen.count(name))
        throw DataError(file, table.header_line, column_of(c),
                        "duplicate column '" + name + "' (also column " + std::to_string(seen[name] + 1) + ")");
      seen[name] = c;
      table.header.push_back(name);
    }
    break;
  }
  if (!any_line) throw DataError(file, 0, 0, "empty file");
  if (table.header.empty()) throw DataError(file, reader.line_number(), 0, "no header row (only comments)");

  table.columns.resize(table.header.size());
  while (reader.next(line)) {
    const std::string_view text = trim(line);
    const int at = reader.line_number();
    if (text.empty()) continue;
    if (text.front() == '#')
      throw DataError(file, at, 1, "comment lines are allowed only before the header");
    const auto fields = split_fields(text);
    if (fields.size() != table.header.size())
      throw DataError(file, at, column_of(std::min(fields.size(), table.header.size())),
                      "row has " + std::to_string(fields.size()) + " fields, the header has " +
                          std::to_string(table.header.size()));
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const auto value = parse_number(fields[c]);
      const std::string where = " in column '" + table.header[c] + "'";
      if (!value)
        throw DataError(file, at, column_of(c), "'" + std::string(fields[c]) + "' is not a number" + where);
      if (!std::isfinite(*value))
        throw DataError(file, at, column_of(c),
                        "'" + std::string(fields[c]) + "' is not finite (NaN or infinity)" + where);
      if (std::abs(*value) > kMaxDataMagnitude)
        throw DataError(file, at, column_of(c), too_large_message(fields[c]) + where);
      table.columns[c].push_back(*value);
    }
    table.row_lines.push_back(at);
  }
  if (table.row_lines.empty()) throw DataError(file, table.header_line, 0, "no data rows after the header");
  return table;
}

}  // namespace mbgen::data_detail
