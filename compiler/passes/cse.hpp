// Common-subexpression elimination over GiNaC expression trees: the pass the C++ emitter and the in-process
// evaluator's tapes both run on the derived expressions.
//
// Nodes are identified by their sign-free key (sign_free_key.hpp), so that e and -e are one node; uses are
// counted over the DAG, and every non-trivial node used more than once is hoisted into a temporary symbol that
// holds its magnitude (each use is then ±the temporary). Temporaries come in dependency order (post-order of a
// depth-first walk of the outputs in their given order, operands in key order). GiNaC's own operand order and the
// signs it gives sums in products follow hash values, which change from run to run; keys do not, so the
// temporaries and their numbering are the same in every run.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

namespace mbgen::passes {

struct CseResult {
  // temporaries[i] = {symbol, definition}; a definition may use earlier temporaries only.
  std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> temporaries;
  std::vector<GiNaC::ex> outputs;  // the inputs, rewritten over the temporaries
};

// Temporaries are named prefix + index ("t0", "t1", ...).
CseResult eliminate_common_subexpressions(const std::vector<GiNaC::ex>& expressions, const std::string& prefix = "t");

}  // namespace mbgen::passes
