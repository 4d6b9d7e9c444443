// Errors raised by the numeric dynamics (singular mass matrix, inconsistent sizes, bad sampling).
#pragma once

#include <stdexcept>
#include <string>

namespace mbgen {

class DynamicsError : public std::runtime_error {
 public:
  explicit DynamicsError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace mbgen
