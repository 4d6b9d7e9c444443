// User text in emitted C++: string literals, comments, #include lines and namespace names. Every string that comes
// from a user (a file name, a unit, a model name, --namespace) reaches the generated code through one of these, so
// that it can neither end a literal or a comment early nor form a trigraph or a line splice.
#pragma once

#include <string>
#include <string_view>

namespace mbgen::emit {

// A C++ string literal (with its quotes) that denotes exactly `s`: quotes, backslashes and `?` (trigraphs) escaped,
// other bytes outside printable ASCII as three-digit octal escapes.
std::string cxx_string_literal(std::string_view s);

// `s` made safe inside a `//` comment: printable ASCII and valid UTF-8 kept, a backslash or `?` (a line splice,
// directly or as the trigraph ??/) and every other byte written as \xNN.
std::string cxx_comment_text(std::string_view s);

// Empty if `name` can stand between the quotes of `#include "..."` (where no escapes exist), else why not.
std::string include_name_problem(std::string_view name);

// Empty if `ns` (A or A::B::C) is a usable namespace for generated code, else why not: each part passes
// ir::cxx_identifier_problem (an identifier, not a keyword, macro, reserved name or namespace the code uses), and the
// first, declared at global scope, ir::cxx_top_namespace_problem (not a name the included headers declare there).
std::string namespace_problem(std::string_view ns);

}  // namespace mbgen::emit
