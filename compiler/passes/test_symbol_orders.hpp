// Test helpers: the same expressions over symbols created in every order. GiNaC hashes a symbol by its serial
// number, so the creation order decides GiNaC's operand order and the signs it gives sums in products, as the load
// address does between two runs of a program: what must be deterministic must not change with the order.
#pragma once

#include <ginac/ginac.h>

#include <algorithm>
#include <array>
#include <sstream>
#include <string>
#include <vector>

namespace mbgen::passes::test {

// Four symbols created in the order `order` gives: GiNaC hashes a symbol by its serial number, so the creation
// order decides GiNaC's operand order and the signs it gives sums in products, as the load address does between
// two runs of a program.
struct OrderedSymbols {
  explicit OrderedSymbols(const std::array<int, 4>& order) {
    const char* const names[] = {"a", "b", "c", "d"};
    for (int i : order) s[static_cast<std::size_t>(i)] = GiNaC::symbol(names[i]);
  }
  std::array<GiNaC::symbol, 4> s;
};

// Expressions whose sums GiNaC signs by hash order: products, integer powers and quotients of differences.
inline std::vector<GiNaC::ex> rational_expressions(const OrderedSymbols& y) {
  const auto& [a, b, c, d] = y.s;
  return {c * (a - b),
          (b - a) * c * d / (c - d),
          GiNaC::pow(a - b + 2 * d, -3) * c,
          GiNaC::pow(a - b, 2) / (d - c),
          a * c / (b - a) + d * (c - d) / (a + b - c),
          GiNaC::sqrt(a - b) * (c - d)};
}

inline std::vector<std::array<int, 4>> creation_orders() {
  std::vector<std::array<int, 4>> orders;
  std::array<int, 4> order = {0, 1, 2, 3};
  do orders.push_back(order);
  while (std::next_permutation(order.begin(), order.end()));
  return orders;
}

// GiNaC's own text of the expressions: it differs between creation orders (or the tests below prove nothing).
inline std::string ginac_text(const std::vector<GiNaC::ex>& es) {
  std::ostringstream text;
  for (const auto& e : es) text << e << ";";
  return text.str();
}

}  // namespace mbgen::passes::test
