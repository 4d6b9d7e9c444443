#include "emit/cxx_text.hpp"

#include <cstdio>

#include "ir/identifier.hpp"

namespace mbgen::emit {

namespace {

bool printable_ascii(unsigned char c) { return c >= 0x20 && c < 0x7f; }

std::string hex_escape(unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02X", c);
  return buf;
}

// Length of the valid UTF-8 sequence (2 to 4 bytes, no overlong forms or surrogates) at s[i], or 0.
std::size_t utf8_sequence(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // range of the second byte
  if (c >= 0xC2 && c <= 0xDF) n = 2;
  else if (c == 0xE0) n = 3, lo = 0xA0;
  else if (c == 0xED) n = 3, hi = 0x9F;
  else if (c >= 0xE1 && c <= 0xEF) n = 3;
  else if (c == 0xF0) n = 4, lo = 0x90;
  else if (c == 0xF4) n = 4, hi = 0x8F;
  else if (c >= 0xF1 && c <= 0xF3) n = 4;
  if (n == 0 || i + n > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

}  // namespace

std::string cxx_string_literal(std::string_view s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\' || c == '?') {
      out += '\\';
      out += ch;
    } else if (printable_ascii(c)) {
      out += ch;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\%03o", c);  // octal: at most three digits, so no following digit joins it
      out += buf;
    }
  }
  return out + "\"";
}

std::string cxx_comment_text(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (printable_ascii(c) && c != '\\' && c != '?') {
      out += s[i++];
      continue;
    }
    if (const std::size_t n = c >= 0x80 ? utf8_sequence(s, i) : 0) {
      out.append(s.substr(i, n));
      i += n;
      continue;
    }
    out += hex_escape(c);
    ++i;
  }
  return out;
}

std::string include_name_problem(std::string_view name) {
  if (name.empty()) return "it is empty";
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c == '"' || c == '\\') return std::string("it contains `") + name[i] + "`, which #include \"...\" cannot hold";
    if (c == '?' && i + 1 < name.size() && name[i + 1] == '?') return "it contains `??` (a trigraph in #include)";
    if (c < 0x20 || c == 0x7f) return "it contains a control character (such as a newline)";
  }
  return "";
}

std::string namespace_problem(std::string_view ns) {
  std::size_t start = 0;
  while (true) {
    const std::size_t sep = ns.find("::", start);
    const std::size_t length = sep == std::string_view::npos ? std::string_view::npos : sep - start;
    if (const std::string problem = ir::cxx_identifier_problem(ns.substr(start, length)); !problem.empty())
      return problem;
    if (sep == std::string_view::npos) return "";
    start = sep + 2;
  }
}

}  // namespace mbgen::emit
