// Errors in measured data files (CSV time records, CSV FRFs, UFF 58). The `mbgen` command prints what() and
// exits with status 1.
#pragma once

#include <stdexcept>
#include <string>

namespace mbgen {

class DataError : public std::runtime_error {
 public:
  // what() reads "FILE:LINE:COLUMN: error: MESSAGE"; LINE and COLUMN are left out when 0 (unknown).
  // COLUMN counts comma-separated fields from 1 in CSV files and characters from 1 in UFF files.
  DataError(const std::string& file, int line, int column, const std::string& message);
  // A message that is not tied to a place in a file.
  explicit DataError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace mbgen
