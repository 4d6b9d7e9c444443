#include "passes/sign_free_key.hpp"

#include <catch2/catch.hpp>

#include <set>

#include "passes/test_symbol_orders.hpp"

using namespace mbgen::passes;
using namespace mbgen::passes::test;


TEST_CASE("an expression and its negative share a key and have opposite signs") {
  GiNaC::symbol a("a"), b("b"), c("c");
  const std::vector<GiNaC::ex> cases = {a,     3 * a,  a - b,     c * (a - b),   GiNaC::pow(a - b, -1),
                                        GiNaC::pow(a - b, 3) * c, (a - b) / (a + c), GiNaC::sqrt(a - b) * c,
                                        GiNaC::sin(a - b)};
  for (const auto& e : cases) {
    SignFreeKeys keys;
    const GiNaC::ex minus = -e;
    INFO(e << " and " << minus);
    CHECK(keys.key(e) == keys.key(minus));
    CHECK(keys.sign(e) == -keys.sign(minus));
    CHECK(keys.sign(keys.sign(e) * e) == 1);
  }
}

TEST_CASE("even powers have no sign, and different values have different keys") {
  GiNaC::symbol a("a"), b("b"), c("c");
  SignFreeKeys keys;
  CHECK(keys.sign(GiNaC::pow(a - b, 2)) == 1);
  CHECK(keys.sign(GiNaC::pow(b - a, 2)) == 1);
  const std::vector<GiNaC::ex> distinct = {a - b,     a + b,        2 * a - b,           GiNaC::pow(a - b, 2),
                                           GiNaC::pow(a - b, 3), GiNaC::sqrt(a - b), GiNaC::sqrt(b - a),
                                           GiNaC::sin(a - b), GiNaC::sin(b - a),   c * (a - b) + c};
  for (std::size_t i = 0; i < distinct.size(); ++i)
    for (std::size_t j = i + 1; j < distinct.size(); ++j) {
      INFO(distinct[i] << " and " << distinct[j]);
      CHECK(keys.key(distinct[i]) != keys.key(distinct[j]));
    }
}

TEST_CASE("keys and signs do not depend on the order GiNaC keeps operands in") {
  const auto orders = creation_orders();
  const OrderedSymbols first(orders.front());
  const std::vector<GiNaC::ex> reference = rational_expressions(first);
  SignFreeKeys reference_keys;
  std::set<std::string> ginac_texts;
  for (const auto& order : orders) {
    const OrderedSymbols y(order);
    const std::vector<GiNaC::ex> es = rational_expressions(y);
    ginac_texts.insert(ginac_text(es));
    SignFreeKeys keys;
    for (std::size_t i = 0; i < es.size(); ++i) {
      INFO("creation order " << order[0] << order[1] << order[2] << order[3] << ": " << es[i]);
      CHECK(keys.key(es[i]) == reference_keys.key(reference[i]));
      CHECK(keys.sign(es[i]) == reference_keys.sign(reference[i]));
    }
  }
  CHECK(ginac_texts.size() > 1);
}
