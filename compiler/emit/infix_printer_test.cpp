#include "emit/infix_printer.hpp"

#include <catch2/catch.hpp>

#include <regex>
#include <set>

#include "passes/test_symbol_orders.hpp"

using namespace mbgen::emit;

namespace {

// The mbgen-inspect/1 syntax: names, integers, + - * / ^ and parentheses, spaces.
bool allowed_syntax(const std::string& s) { return std::regex_match(s, std::regex("[A-Za-z_0-9+\\-*/^() ]*")); }

// Reads the text back with GiNaC's own parser: an independent route to check the meaning.
GiNaC::ex read_back(const std::string& text, const GiNaC::symtab& table) {
  GiNaC::parser reader(table, true);
  return reader(text);
}

}  // namespace

TEST_CASE("infix text uses only the schema syntax and reads back to the same expression") {
  GiNaC::symbol m1("m1"), m2("m2"), k12("k12"), c11("c11");
  const GiNaC::symtab table = {{"m1", m1}, {"m2", m2}, {"k12", k12}, {"c11", c11}};
  const std::vector<GiNaC::ex> cases = {
      GiNaC::numeric(127, 1000),
      GiNaC::numeric(-3),
      1 / m1,
      -k12,
      (k12 + c11) / (m1 * m2),
      GiNaC::pow(m1, -2) * k12,
      GiNaC::numeric(127, 1000) * m1 - GiNaC::numeric(1, 3) * GiNaC::pow(m2, 3),
      GiNaC::sqrt(GiNaC::ex(2)) / 2 * k12,  // ex: GiNaC::sqrt(numeric) would evaluate to a float,
      GiNaC::pow(m1 + m2, GiNaC::numeric(-1, 2)),
      -(m1 + m2) * c11,
      GiNaC::pow(-m1, 3),
  };
  for (const auto& e : cases) {
    const std::string text = infix_text(e);
    INFO(text);
    CHECK(allowed_syntax(text));
    CHECK(text.find("^(-") == std::string::npos);
    CHECK((read_back(text, table) - e).expand().is_zero());
  }
  CHECK(infix_text(GiNaC::numeric(127, 1000)) == "127/1000");
  CHECK(infix_text(1 / m1) == "1/m1");
  CHECK(infix_text(GiNaC::numeric(-5, 2) * m1) == "-5*m1/2");
  CHECK(infix_text(GiNaC::pow(m1, 2)) == "m1^2");
  CHECK(infix_text(GiNaC::sqrt(m1)) == "m1^(1/2)");
}

TEST_CASE("floating-point numbers are written as the exact ratio they hold") {
  const std::string text = infix_text(GiNaC::numeric(0.1));
  CHECK(text == "3602879701896397/36028797018963968");
}

TEST_CASE("the text does not depend on the order the symbols were created in") {
  using namespace mbgen::passes::test;
  std::vector<std::string> reference;
  std::set<std::string> ginac_texts;
  for (const auto& order : creation_orders()) {
    const OrderedSymbols y(order);
    const std::vector<GiNaC::ex> exprs = rational_expressions(y);
    ginac_texts.insert(ginac_text(exprs));
    const GiNaC::symtab table = {{"a", y.s[0]}, {"b", y.s[1]}, {"c", y.s[2]}, {"d", y.s[3]}};
    std::vector<std::string> texts;
    for (const auto& e : exprs) {
      texts.push_back(infix_text(e));
      INFO(texts.back());
      CHECK(GiNaC::normal(read_back(texts.back(), table) - e).is_zero());
    }
    if (reference.empty()) reference = texts;
    INFO("creation order " << order[0] << order[1] << order[2] << order[3]);
    CHECK(texts == reference);
  }
  CHECK(ginac_texts.size() > 1);
  // The sign of a sum in a product is that of its first term in key order (sign_free_key.hpp).
  GiNaC::symbol a("a"), b("b"), c("c");
  CHECK(infix_text(c * (b - a)) == "-(a - b)*c");
  CHECK(infix_text(GiNaC::pow(b - a, -3)) == "-1/(a - b)^3");
}
