// Uncoupled blocks of the equations of motion (internal).
#pragma once

#include <ginac/ginac.h>

#include <vector>

namespace mbgen::symbolic {

// Connected components of the graph with an edge i-j wherever one of `matrices` has a structurally non-zero
// (i, j) entry. Each block is sorted; blocks are ordered by their smallest coordinate index.
std::vector<std::vector<int>> uncoupled_blocks(const std::vector<const GiNaC::matrix*>& matrices, int n);

}  // namespace mbgen::symbolic
