#include "mbgen/report/report_files.hpp"

#include "mbgen/estimation/fit.hpp"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace mbgen {

void write_report_file(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw FitError("cannot write " + tmp.string());
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw FitError("cannot write " + path + ": " + ec.message());
}

std::string file_stem(const std::string& name) {
  std::string out;
  for (char c : name) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '_';
  return out;
}

std::string report_number(double x, int digits) {
  if (!std::isfinite(x)) return "n/a";
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

}  // namespace mbgen
