#include "mbgen/report/markdown.hpp"

#include <algorithm>
#include <cstring>

#include "text/string_format.hpp"

namespace mbgen {

namespace {

bool control(unsigned char c) { return c < 0x20 || c == 0x7f; }

std::string hex(unsigned char c) { return detail::format("\\x%02X", c); }

}  // namespace

std::string markdown_text(std::string_view s) {
  std::string out;
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (control(c)) {
      out += "\\" + hex(c);  // the backslash itself escaped: \x0A shows as written
    } else {
      // Markup that can begin mid-line: emphasis, code, links and images, raw HTML, entities, table cells.
      if (std::strchr("\\`*_[]<>|~&!", ch)) out += '\\';
      out += ch;
    }
  }
  return out;
}

std::string markdown_code(std::string_view s) {
  std::string body;
  std::size_t run = 0, longest = 0;
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    run = ch == '`' ? run + 1 : 0;
    longest = std::max(longest, run);
    if (control(c)) body += hex(c);
    else if (ch == '|') body += "\\|";  // GitHub tables split cells at `|` even inside code spans
    else body += ch;
  }
  const std::string fence(longest + 1, '`');
  // A space inside the fence keeps a backtick at either end of the text from joining it (the space is dropped).
  const bool pad = !body.empty() && (body.front() == '`' || body.back() == '`');
  return fence + (pad ? " " : "") + body + (pad ? " " : "") + fence;
}

}  // namespace mbgen
