// Identifiers: of the model language, and the C++ identifiers that user names become in generated code (a model's
// namespace, its parameters' variables). Every place that checks or makes one uses these, so that the rules (and
// the list of C++ keywords) live here only.
#pragma once

#include <string>
#include <string_view>

namespace mbgen::ir {

// A letter or `_`, then letters, digits or `_` (ASCII): a name of the model language.
bool is_identifier(std::string_view s);

// The identifier made from arbitrary text (a file's stem): every other character becomes `_`, and `m_` goes in
// front of a leading digit or an empty result.
std::string to_identifier(std::string_view s);

// Names the model language gives a meaning of their own in expressions (the constant pi, the open bound inf): no
// parameter may take them.
bool is_reserved_name(std::string_view s);
// The other words of the language (functions, coordinates, roles, `in`): legal names, but confusing ones that
// mbgen never picks for a name of its own.
bool is_language_word(std::string_view s);

// Empty if `s` can name something the generated C++ declares (one part of a namespace), else why not: an
// identifier that is not a C++ keyword, not a macro that GNU mode or the included headers define (`linux`,
// `NULL`), not reserved (`__`, `_` and a capital), and not a namespace the generated code refers to unqualified
// (std, Eigen, mbgen, mpfr), which it would hide.
std::string cxx_identifier_problem(std::string_view s);

// The same for the first part of a namespace, which is declared at global scope: also not a name the headers the
// generated code includes declare there (sin, y0, FILE, size_t).
std::string cxx_top_namespace_problem(std::string_view s);

// The C++ variable that holds parameter `name` in generated code.
std::string cxx_parameter_variable(std::string_view name);

}  // namespace mbgen::ir
