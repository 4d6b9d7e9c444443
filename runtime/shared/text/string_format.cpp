#include "text/string_format.hpp"

#include <cstdarg>
#include <cstdio>

namespace mbgen::detail {

std::string format(const char* pattern, ...) {
  va_list args;
  va_start(args, pattern);
  va_list again;
  va_copy(again, args);
  char small[256];
  const int length = std::vsnprintf(small, sizeof small, pattern, args);
  va_end(args);
  std::string out;
  if (length < 0) {  // an encoding error; not reached with the runtime's patterns
    va_end(again);
    return out;
  }
  if (static_cast<std::size_t>(length) < sizeof small) {
    va_end(again);
    return std::string(small, static_cast<std::size_t>(length));
  }
  out.resize(static_cast<std::size_t>(length) + 1);
  std::vsnprintf(out.data(), out.size(), pattern, again);
  va_end(again);
  out.resize(static_cast<std::size_t>(length));
  return out;
}

}  // namespace mbgen::detail
