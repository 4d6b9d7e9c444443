#include "passes/cse.hpp"

#include <catch2/catch.hpp>

using namespace mbgen::passes;

namespace {

// Substitutes the temporaries back, innermost last, to recover the expressions CSE started from.
std::vector<GiNaC::ex> expand_temporaries(const CseResult& r) {
  std::vector<GiNaC::ex> out = r.outputs;
  for (auto it = r.temporaries.rbegin(); it != r.temporaries.rend(); ++it)
    for (auto& e : out) e = e.subs(GiNaC::exmap{{it->first, it->second}});
  return out;
}

}  // namespace

TEST_CASE("CSE hoists repeated non-trivial subexpressions and keeps the value") {
  GiNaC::symbol a("a"), b("b"), c("c");
  const GiNaC::ex shared = a * b + c;
  const std::vector<GiNaC::ex> exprs = {GiNaC::pow(shared, 2) * a, 3 / shared + b, GiNaC::sin(shared), a};
  const CseResult r = eliminate_common_subexpressions(exprs);
  REQUIRE(!r.temporaries.empty());
  bool found = false;
  for (const auto& [sym, def] : r.temporaries) found = found || def.is_equal(shared);
  CHECK(found);
  const auto back = expand_temporaries(r);
  for (std::size_t i = 0; i < exprs.size(); ++i) CHECK((back[i] - exprs[i]).expand().is_zero());
  // Leaves and number-times-leaf are never hoisted.
  const CseResult trivial = eliminate_common_subexpressions({-a, -a, b, b});
  CHECK(trivial.temporaries.empty());
}

TEST_CASE("a sum used with both signs is one temporary") {
  GiNaC::symbol a("a"), b("b"), c("c");
  const GiNaC::ex d = a - b;
  const CseResult r = eliminate_common_subexpressions({d * c, -d * c * c, d * b, 1 / (-d)});
  CHECK(r.temporaries.size() == 1);
}

TEST_CASE("temporaries are named by the prefix, in dependency order") {
  GiNaC::symbol a("a"), b("b"), c("c");
  const GiNaC::ex inner = a + b, outer = inner * inner * c + 1;
  const CseResult r = eliminate_common_subexpressions({outer, outer * a, inner}, "tape_t");
  REQUIRE(r.temporaries.size() == 2);
  CHECK(r.temporaries[0].first.get_name() == "tape_t0");
  CHECK(r.temporaries[1].first.get_name() == "tape_t1");
  CHECK(!r.temporaries[0].second.has(r.temporaries[1].first));
  CHECK(r.temporaries[1].second.has(r.temporaries[0].first));
}
