#include "emit/infix_printer.hpp"

#include <catch2/catch.hpp>

#include <regex>

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
