#include "frontend/diagnostics.hpp"

#include "frontend/message.hpp"

namespace mbgen::frontend {

std::string error_text(std::string_view file, ir::SourceLoc loc, std::string_view text) {
  const std::string_view where = file.empty() ? std::string_view("<model>") : file;
  if (loc.line <= 0) return fmt::format("{}: error: {}", where, text);
  return fmt::format("{}:{}:{}: error: {}", where, loc.line, loc.column, text);
}

ModelError::ModelError(const std::string& file, ir::SourceLoc loc, const std::string& message)
    : std::runtime_error(error_text(file, loc, std::string_view(message))), file_(file), loc_(loc), message_(message) {}

}  // namespace mbgen::frontend
