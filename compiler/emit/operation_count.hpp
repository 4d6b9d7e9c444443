// Arithmetic operations of an expression as the C++ printer writes it (cxx_printer.hpp), for the counts the
// generated file's banner reports before and after common-subexpression elimination.
//
// Counted: a sum or product of k operands as k - 1 operations (a numeric coefficient is an operand; so is a
// negative sign folded into it), x^k for an integer 2 <= |k| <= 4 as |k| - 1 multiplications (and one division if
// k < 0), any other power and every function call (sin, cos, sqrt, pow, ...) as 1, a non-integer rational number
// as 1 (it is printed as a quotient). Leaves cost nothing. An expression is counted as a tree: a subexpression
// that occurs twice counts twice (that is what CSE removes), so the count before CSE is the cost of evaluating
// each output on its own.
#pragma once

#include <ginac/ginac.h>

#include <cstddef>
#include <map>

namespace mbgen::emit {

class OperationCounter {
 public:
  // Operations of e as a tree. Memoised per node: a derivative tree that shares subtrees is counted in time
  // linear in its distinct nodes.
  std::size_t count(const GiNaC::ex& e);

 private:
  std::map<GiNaC::ex, std::size_t, GiNaC::ex_is_less> memo_;
};

// Totals over the emitted functions of a model.
struct OperationCounts {
  std::size_t before_cse = 0;  // every output evaluated as its own tree
  std::size_t after_cse = 0;   // the emitted statements: temporaries' definitions and the outputs over them
};

}  // namespace mbgen::emit
