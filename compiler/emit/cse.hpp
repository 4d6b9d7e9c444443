// Common-subexpression elimination over GiNaC expression trees, for the C++ emitter.
//
// Expressions are hash-consed (std::map with GiNaC::ex_is_less, so structurally equal subtrees are one node),
// uses are counted over the DAG, and every non-trivial node used more than once is hoisted into a temporary
// symbol. Temporaries come in dependency order (post-order of a depth-first walk of the outputs in their
// given order), so the result is deterministic for a given input.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

namespace mbgen::emit {

struct CseResult {
  // temporaries[i] = {symbol, definition}; a definition may use earlier temporaries only.
  std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> temporaries;
  std::vector<GiNaC::ex> outputs;  // the inputs, rewritten over the temporaries
};

// Temporaries are named prefix + index ("t0", "t1", ...).
CseResult eliminate_common_subexpressions(const std::vector<GiNaC::ex>& expressions, const std::string& prefix = "t");

}  // namespace mbgen::emit
