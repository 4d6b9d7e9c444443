#include "emit/cxx_text.hpp"

#include <cstdio>

#include "ir/identifier.hpp"

#include "text/utf8.hpp"

namespace mbgen::emit {

namespace {

bool printable_ascii(unsigned char c) { return c >= 0x20 && c < 0x7f; }

std::string hex_escape(unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02X", c);
  return buf;
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
    if (const std::size_t n = c >= 0x80 ? utf8_sequence_length(s, i) : 0) {
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
    const std::string_view part = ns.substr(start, length);
    if (const std::string problem = start == 0 ? ir::cxx_top_namespace_problem(part) : ir::cxx_identifier_problem(part);
        !problem.empty())
      return problem;
    if (sep == std::string_view::npos) return "";
    start = sep + 2;
  }
}

}  // namespace mbgen::emit
