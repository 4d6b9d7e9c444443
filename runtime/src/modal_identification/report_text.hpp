// What the modal reports (modal_report.cpp, output_only_report.cpp) share: writing a report file, numbers as text,
// and the stabilization diagram's pole codes. Internal header.
#pragma once

#include "mbgen/modal_identification/modal_identification.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

#include "text/string_format.hpp"

namespace mbgen::modal_text {

inline void write_file(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(path + ": error: cannot write the report");
}

// `digits` significant digits; "n/a" for NaN and infinities.
inline std::string num(double x, int digits = 4) {
  if (!std::isfinite(x)) return "n/a";
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

inline std::string fixed(double x, int decimals) {
  return std::isfinite(x) ? detail::format("%.*f", decimals, x) : "n/a";
}

// The gnuplot data's code of a diagram pole: 0 new ... 4 stable.
inline int stability_code(DiagramPole::Stability s) {
  using Stability = DiagramPole::Stability;
  switch (s) {
    case Stability::New: return 0;
    case Stability::Frequency: return 1;
    case Stability::FrequencyDamping: return 2;
    case Stability::FrequencyShape: return 3;
    case Stability::Stable: return 4;
  }
  return 0;
}

}  // namespace mbgen::modal_text
