#include "ir/identifier.hpp"

namespace mbgen::ir {

namespace {
bool letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool digit(char c) { return c >= '0' && c <= '9'; }
}  // namespace

bool is_identifier(std::string_view s) {
  if (s.empty() || !letter(s.front())) return false;
  for (char c : s)
    if (!letter(c) && !digit(c)) return false;
  return true;
}

std::string to_identifier(std::string_view s) {
  std::string out;
  for (char c : s) out += letter(c) || digit(c) ? c : '_';
  if (out.empty() || digit(out.front())) out = "m_" + out;
  return out;
}

}  // namespace mbgen::ir
