#include "emit/cxx_printer.hpp"

#include <catch2/catch.hpp>

#include <set>

#include "passes/cse.hpp"
#include "passes/test_symbol_orders.hpp"

using namespace mbgen::emit;
namespace passes = mbgen::passes;

namespace {

struct Symbols {
  GiNaC::symbol a{"a"}, b{"b"}, c{"c"};
  SymbolNames names{{a, "p_a"}, {b, "p_b"}, {c, "p_c"}};
};

// Substitutes the temporaries back, innermost last, to recover the expressions CSE started from.
std::vector<GiNaC::ex> expand_temporaries(const passes::CseResult& r) {
  std::vector<GiNaC::ex> out = r.outputs;
  for (auto it = r.temporaries.rbegin(); it != r.temporaries.rend(); ++it)
    for (auto& e : out) e = e.subs(GiNaC::exmap{{it->first, it->second}});
  return out;
}

}  // namespace

TEST_CASE("exact numbers print as Scalar arithmetic, never integer division") {
  CHECK(cxx_number(GiNaC::numeric(127, 1000)) == "Scalar(127)/Scalar(1000)");
  CHECK(cxx_number(GiNaC::numeric(-3, 4)) == "-Scalar(3)/Scalar(4)");
  CHECK(cxx_number(GiNaC::numeric(42)) == "Scalar(42)");
  CHECK(cxx_number(GiNaC::numeric(0)) == "Scalar(0)");
  // 10^20 + 7 does not fit a 64-bit literal: split in base 10^15.
  CHECK(cxx_number(GiNaC::numeric("100000000000000000007")) ==
        "(Scalar(100000)*Scalar(1000000000000000) + Scalar(7))");
}

TEST_CASE("expressions print with Scalar numbers, products for small powers and unqualified calls") {
  Symbols s;
  CHECK(cxx_expression(GiNaC::numeric(1, 3) * s.a, s.names) == "Scalar(1)/Scalar(3)*p_a");
  CHECK(cxx_expression(s.a - s.b, s.names) == "p_a - p_b");
  CHECK(cxx_expression(GiNaC::pow(s.a, 3), s.names) == "p_a*p_a*p_a");
  CHECK(cxx_expression(GiNaC::pow(s.a, 7), s.names) == "pow(p_a, Scalar(7))");
  CHECK(cxx_expression(GiNaC::sqrt(s.a), s.names) == "sqrt(p_a)");
  CHECK(cxx_expression(GiNaC::sin(s.a), s.names) == "sin(p_a)");
  CHECK(cxx_expression(2 * GiNaC::Pi * s.a, s.names) == "Scalar(2)*c_pi*p_a");
  const std::string q = cxx_expression(s.a / (s.b * s.c), s.names);
  CHECK((q == "p_a/(p_b*p_c)" || q == "p_a/(p_c*p_b)"));
  CHECK(cxx_expression(1 / (s.a + s.b), s.names) == "Scalar(1)/(p_a + p_b)");
  CHECK_THROWS_AS(cxx_expression(GiNaC::symbol("unknown"), s.names), std::logic_error);
}

TEST_CASE("the emitted statements compute a repeated subexpression once, in a temporary") {
  Symbols s;
  const GiNaC::ex shared = s.a * s.b + s.c;
  const std::vector<GiNaC::ex> exprs = {GiNaC::pow(shared, 2) * s.a, 3 / shared + s.b, GiNaC::sin(shared)};
  const std::string code = cxx_assignments({{"y0", exprs[0]}, {"y1", exprs[1]}, {"y2", exprs[2]}}, s.names, "  ");
  CHECK(code.find("const Scalar t0 = ") != std::string::npos);
  std::size_t count = 0;
  for (std::size_t pos = code.find("p_c"); pos != std::string::npos; pos = code.find("p_c", pos + 1)) ++count;
  CHECK(count == 1);
}

TEST_CASE("the emitted statements do not depend on the order the symbols were created in") {
  using namespace mbgen::passes::test;
  const auto orders = creation_orders();
  std::string reference;
  std::set<std::string> ginac_texts;
  for (const auto& order : orders) {
    const OrderedSymbols y(order);
    const SymbolNames names{{y.s[0], "p_a"}, {y.s[1], "p_b"}, {y.s[2], "p_c"}, {y.s[3], "p_d"}};
    std::vector<GiNaC::ex> exprs = rational_expressions(y);
    // Shared subexpressions with both signs: temporaries.
    exprs.push_back(exprs[0] * exprs[1] - exprs[2]);
    exprs.push_back(exprs[3] / exprs[4]);
    ginac_texts.insert(ginac_text(exprs));
    std::vector<CxxAssignment> as;
    for (std::size_t i = 0; i < exprs.size(); ++i) as.push_back({"y" + std::to_string(i), exprs[i]});
    const std::string code = cxx_assignments(as, names, "");
    if (reference.empty()) reference = code;
    INFO("creation order " << order[0] << order[1] << order[2] << order[3]);
    CHECK(code == reference);

    const passes::CseResult r = passes::eliminate_common_subexpressions(exprs);
    const auto back = expand_temporaries(r);
    for (std::size_t i = 0; i < exprs.size(); ++i) CHECK(GiNaC::normal(back[i] - exprs[i]).is_zero());
  }
  CHECK(ginac_texts.size() > 1);
}

TEST_CASE("CSE is deterministic") {
  Symbols s;
  const std::vector<GiNaC::ex> exprs = {GiNaC::pow(s.a + s.b, 2) + 1 / (s.a + s.b), (s.a + s.b) * s.c * (s.b - s.c),
                                        (s.b - s.c) / (s.a + s.b)};
  std::vector<CxxAssignment> as;
  for (std::size_t i = 0; i < exprs.size(); ++i) as.push_back({"y" + std::to_string(i), exprs[i]});
  CHECK(cxx_assignments(as, s.names, "") == cxx_assignments(as, s.names, ""));
}
