#include "mbgen/data_error.hpp"

namespace mbgen {

namespace {
std::string locate(const std::string& file, int line, int column, const std::string& message) {
  std::string where = file.empty() ? std::string("<data>") : file;
  if (line > 0) {
    where += ":" + std::to_string(line);
    if (column > 0) where += ":" + std::to_string(column);
  }
  return where + ": error: " + message;
}
}  // namespace

DataError::DataError(const std::string& file, int line, int column, const std::string& message)
    : std::runtime_error(locate(file, line, column, message)) {}

}  // namespace mbgen
