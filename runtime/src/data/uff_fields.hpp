// Fixed-width fields of the UFF writers (uff58_write.cpp, uff55_write.cpp): the specification's Fortran formats,
// which other readers (pyuff, commercial analysers) parse by column.
#pragma once

#include <cstdio>
#include <string>

namespace mbgen::uff_detail {

// A field of `width` characters: text cut to `width`, left-aligned.
inline std::string text_field(const std::string& text, std::size_t width) {
  std::string t = text.substr(0, width);
  return t + std::string(width - t.size(), ' ');
}

// `v` in a printf format such as "%13.5E" (Fortran E13.5 with six significant digits); never "-0".
inline std::string format(const char* spec, double v) {
  char out[64];
  std::snprintf(out, sizeof out, spec, v == 0 ? 0.0 : v);
  return out;
}

// Fortran Iw: right-aligned in `width` characters.
inline std::string integer(long v, int width) {
  char out[32];
  std::snprintf(out, sizeof out, "%*ld", width, v);
  return out;
}

}  // namespace mbgen::uff_detail
