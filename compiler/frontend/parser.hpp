// The .mdl parser: text -> checked ir::ModelIr. Grammar and rules: docs/language.md.
#pragma once

#include <cstddef>
#include <string>

#include "ir/model_ir.hpp"

namespace mbgen::frontend {

// The largest model file read (docs/limits.md): 16 MiB is some 300 000 lines, far beyond any model whose equations
// can be derived; without a bound, `inspect /dev/zero` read until the memory ran out.
inline constexpr std::size_t kMaxModelBytes = std::size_t(16) << 20;

// The text of a model file ("-" reads standard input). Throws ModelError when it cannot be read (or is a directory,
// or larger than kMaxModelBytes).
std::string read_model_text(const std::string& path);

// Reads and parses a model file ("-" reads standard input). Throws ModelError naming file, line and column.
ir::ModelIr parse_file(const std::string& path);

// Parses model text; `file_name` is used in messages and stored in the model.
ir::ModelIr parse_string(const std::string& text, const std::string& file_name);

}  // namespace mbgen::frontend
