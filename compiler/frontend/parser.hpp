// The .mdl parser: text -> checked ir::Model. Grammar and rules: docs/language.md.
#pragma once

#include <string>

#include "ir/model.hpp"

namespace mbgen::frontend {

// The text of a model file ("-" reads standard input). Throws ModelError when it cannot be read (or is a directory).
std::string read_model_text(const std::string& path);

// Reads and parses a model file ("-" reads standard input). Throws ModelError naming file, line and column.
ir::Model parse_file(const std::string& path);

// Parses model text; `file_name` is used in messages and stored in the model.
ir::Model parse_string(const std::string& text, const std::string& file_name);

}  // namespace mbgen::frontend
