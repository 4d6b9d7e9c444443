// GiNaC's own text of an expression, for error messages only (its operand order is not deterministic).
#pragma once

#include <ginac/ginac.h>

#include <sstream>
#include <string>

namespace mbgen::emit {

inline std::string ginac_text(const GiNaC::ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

}  // namespace mbgen::emit
