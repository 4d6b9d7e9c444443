// User text (file names, names, units) in Markdown reports: it must not start a heading, a link, raw HTML or a new
// table cell. Text written in a table cell needs no more than this.
#pragma once

#include <string>
#include <string_view>

namespace mbgen {

// `s` as literal Markdown text: ASCII punctuation that Markdown could read as markup (including `|`) escaped with
// a backslash, control characters (a newline in a file name) written as \xNN.
std::string markdown_text(std::string_view s);

// `s` as a code span (`...`), also inside a table: the fence longer than any run of backticks in `s`, `|`
// escaped, control characters written as \xNN.
std::string markdown_code(std::string_view s);

}  // namespace mbgen
