// Errors in a model, located in its file. Every stage (parser, checks, derivation) throws ModelError; the
// `mbgen` command prints what() and exits with status 1.
#pragma once

#include <fmt/format.h>

#include <stdexcept>
#include <string>
#include <utility>

#include "ir/model_ir.hpp"

namespace mbgen::frontend {

class ModelError : public std::runtime_error {
 public:
  // what() reads "FILE:LINE:COLUMN: error: MESSAGE" (LINE:COLUMN left out when loc has no line; message.hpp).
  ModelError(const std::string& file, ir::SourceLoc loc, const std::string& message);
  // The message formatted by fmt: ModelError(file, loc, "unknown body `{}`", name).
  template <typename... Args>
  ModelError(const std::string& file, ir::SourceLoc loc, fmt::format_string<Args...> format, Args&&... args)
      : ModelError(file, loc, fmt::format(format, std::forward<Args>(args)...)) {}
  const std::string& file() const { return file_; }
  ir::SourceLoc loc() const { return loc_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  ir::SourceLoc loc_;
  std::string message_;
};

}  // namespace mbgen::frontend
