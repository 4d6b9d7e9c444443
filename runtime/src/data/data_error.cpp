#include "mbgen/data/data_error.hpp"

namespace mbgen {

namespace {
// Control characters a data file carries (ESC, BEL) are written as \xHH: echoed raw they would drive the user's
// terminal (colours, a cleared screen, a title). Line breaks and tabs of the message itself stay.
std::string printable(const std::string& text) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\n' && c != '\t') || u == 0x7f)
      out += std::string("\\x") + kHex[u >> 4] + kHex[u & 15];
    else
      out += c;
  }
  return out;
}

std::string locate(const std::string& file, int line, int column, const std::string& message) {
  std::string where = file.empty() ? std::string("<data>") : file;
  if (line > 0) {
    where += ":" + std::to_string(line);
    if (column > 0) where += ":" + std::to_string(column);
  }
  return printable(where + ": error: " + message);
}
}  // namespace

DataError::DataError(const std::string& file, int line, int column, const std::string& message)
    : std::runtime_error(locate(file, line, column, message)) {}

}  // namespace mbgen
