// The one way the compiler side writes an error message (docs/cli.md): "FILE:LINE:COLUMN: error: TEXT", LINE and
// COLUMN left out where unknown, TEXT formatted by fmt ("unknown body `{}`", name) rather than concatenated.
// ModelError (diagnostics.hpp), the command's output and manifest errors and the fit command's data errors all
// take their what() from here.
#pragma once

#include <fmt/format.h>

#include <string>
#include <string_view>
#include <utility>

#include "ir/model_ir.hpp"

namespace mbgen::frontend {

// "FILE:LINE:COLUMN: error: TEXT", or "FILE: error: TEXT" when loc has no line; `<model>` for an empty file name.
std::string error_text(std::string_view file, ir::SourceLoc loc, std::string_view text);

template <typename... Args>
std::string error_text(std::string_view file, ir::SourceLoc loc, fmt::format_string<Args...> format, Args&&... args) {
  return error_text(file, loc, std::string_view(fmt::format(format, std::forward<Args>(args)...)));
}

// "FILE: error: TEXT": a message about a whole file.
template <typename... Args>
std::string error_text(std::string_view file, fmt::format_string<Args...> format, Args&&... args) {
  return error_text(file, ir::SourceLoc{}, std::string_view(fmt::format(format, std::forward<Args>(args)...)));
}

}  // namespace mbgen::frontend
