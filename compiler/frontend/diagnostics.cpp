#include "frontend/diagnostics.hpp"

#include <fmt/format.h>

namespace mbgen::frontend {

namespace {
std::string format_error(const std::string& file, ir::SourceLoc loc, const std::string& message) {
  const std::string where = file.empty() ? std::string("<model>") : file;
  if (loc.line <= 0) return fmt::format("{}: error: {}", where, message);
  return fmt::format("{}:{}:{}: error: {}", where, loc.line, loc.column, message);
}
}  // namespace

ModelError::ModelError(const std::string& file, ir::SourceLoc loc, const std::string& message)
    : std::runtime_error(format_error(file, loc, message)), file_(file), loc_(loc), message_(message) {}

}  // namespace mbgen::frontend
