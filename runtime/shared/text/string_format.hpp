// printf-style formatting into a std::string, for the whole runtime (which keeps to the standard library and Eigen,
// so no fmt). One helper instead of a private one per file and fixed-size buffers that cut long texts short.
#pragma once

#include <string>

namespace mbgen::detail {

// The text std::printf(pattern, ...) would print, whatever its length.
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
std::string format(const char* pattern, ...);

}  // namespace mbgen::detail
