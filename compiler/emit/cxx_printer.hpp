// Prints GiNaC expressions as C++ over a template parameter `Scalar`, so the emitted functions work for double,
// long double and multiprecision types (mpfr::mpreal) alike:
//   - exact rationals as Scalar(p)/Scalar(q), integers as Scalar(n): never integer division, never a double
//     literal that would round before the Scalar type sees it (integers beyond 2^53 are split, see .cpp);
//   - x^2..x^4 as products, other integer powers as pow(x, Scalar(k)), x^(1/2) as sqrt(x);
//   - calls unqualified (sqrt, sin, cos, pow, ...), for ADL: the emitted function says `using std::sqrt;` etc.;
//   - the constant pi as the identifier `c_pi`, which the emitted function defines as Scalar(4)*atan(Scalar(1)).
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "emit/operation_count.hpp"

namespace mbgen::emit {

// Symbol -> C++ identifier. A symbol absent from the map is an error (std::logic_error).
using SymbolNames = std::map<GiNaC::ex, std::string, GiNaC::ex_is_less>;

std::string cxx_number(const GiNaC::numeric& n);
std::string cxx_expression(const GiNaC::ex& e, const SymbolNames& names);

struct CxxAssignment {
  std::string lhs;  // e.g. "M(0, 1)"
  GiNaC::ex rhs;
};

// Statements computing all assignments with common subexpressions hoisted:
//   `const Scalar c_pi = ...;` (if pi is used), `const Scalar tN = ...;`, then `lhs = rhs;`.
// Every line starts with `indent` and ends with '\n'. With `counts`, adds the assignments' operations before and
// after the elimination to it (operation_count.hpp).
std::string cxx_assignments(const std::vector<CxxAssignment>& assignments, const SymbolNames& names,
                            const std::string& indent, OperationCounts* counts = nullptr);

}  // namespace mbgen::emit
