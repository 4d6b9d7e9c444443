#include "symbolic/blocks.hpp"

#include <algorithm>
#include <numeric>

namespace mbgen::symbolic {

namespace {

int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<std::vector<int>> uncoupled_blocks(const std::vector<const GiNaC::matrix*>& matrices, int n) {
  std::vector<int> parent(static_cast<size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  for (const GiNaC::matrix* mat : matrices)
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (!(*mat)(i, j).is_zero() || !(*mat)(j, i).is_zero()) {
          const int a = root(parent, i), b = root(parent, j);
          // The smaller index becomes the root, so blocks come out ordered by their first coordinate.
          if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
  std::vector<std::vector<int>> blocks;
  std::vector<int> block_of(static_cast<size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    const int r = root(parent, i);
    if (block_of[r] < 0) {
      block_of[r] = static_cast<int>(blocks.size());
      blocks.emplace_back();
    }
    blocks[block_of[r]].push_back(i);
  }
  return blocks;
}

}  // namespace mbgen::symbolic
