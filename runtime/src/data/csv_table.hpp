// Internal: the part common to CSV time records and FRFs: configuration comments, one header row, and
// rows of finite numbers, all with the same number of fields.
#pragma once

#include <istream>
#include <string>
#include <vector>

#include "text_parsing.hpp"

namespace mbgen::data_detail {

struct CsvTable {
  std::string file;
  DataConfig config;
  int header_line = 0;
  std::vector<std::string> header;            // column names, unique and non-empty
  std::vector<std::vector<double>> columns;   // columns[c][r]
  std::vector<int> row_lines;                 // file line of each row
};

// Throws DataError for: empty file, no header, empty or duplicate column names, comment lines after the
// header, ragged rows, unparsable or non-finite numbers, no data rows.
CsvTable read_csv_table(std::istream& in, const std::string& file);

}  // namespace mbgen::data_detail
