// Text for reports and plots that declare UTF-8: a user's string (a file or channel name in another encoding) may hold
// bytes that are not UTF-8. Such a byte made report.md and report.html invalid UTF-8, and a plot title in gnuplot's
// SVG made the SVG not well-formed XML, so the HTML showed a broken image. The JSON writers replace such bytes the
// same way (nlohmann's error_handler::replace).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace mbgen {

// `s` with each byte that does not start a valid UTF-8 sequence (overlong forms and surrogates are invalid) replaced
// by U+FFFD; valid text is returned unchanged.
std::string valid_utf8(std::string_view s);

// Length of the valid UTF-8 sequence at s[i] (1 for ASCII; 2 to 4 bytes without overlong forms or surrogates), or 0
// when s[i] starts none.
std::size_t utf8_sequence_length(std::string_view s, std::size_t i);

}  // namespace mbgen
