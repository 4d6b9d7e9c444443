// printf-style formatting of up to three numbers into one line of the diagnosis's progress and reasons.
#pragma once

#include <cstdio>
#include <string>

namespace mbgen::diagnosis {

inline std::string format(const char* pattern, double a, double b = 0, double c = 0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, pattern, a, b, c);
  return buffer;
}

}  // namespace mbgen::diagnosis
