// Errors in a model, located in its file. Every stage (parser, checks, derivation) throws ModelError; the
// `mbgen` command prints what() and exits with status 1.
#pragma once

#include <stdexcept>
#include <string>

#include "ir/model.hpp"

namespace mbgen::frontend {

class ModelError : public std::runtime_error {
 public:
  // what() reads "FILE:LINE:COLUMN: error: MESSAGE" (LINE:COLUMN left out when loc has no line).
  ModelError(const std::string& file, ir::SourceLoc loc, const std::string& message);
  const std::string& file() const { return file_; }
  ir::SourceLoc loc() const { return loc_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  ir::SourceLoc loc_;
  std::string message_;
};

}  // namespace mbgen::frontend
