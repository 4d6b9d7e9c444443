// Identifiers of the model language, which also name things in generated C++ (a model's namespace, its parameters).
#pragma once

#include <string>
#include <string_view>

namespace mbgen::ir {

// A letter or `_`, then letters, digits or `_` (ASCII).
bool is_identifier(std::string_view s);

// The identifier made from arbitrary text (a file's stem): every other character becomes `_`, and `m_` goes in
// front of a leading digit or an empty result.
std::string to_identifier(std::string_view s);

}  // namespace mbgen::ir
