#include "mbgen/report/markdown.hpp"

#include <catch2/catch.hpp>

using namespace mbgen;

TEST_CASE("user text in Markdown is literal", "[markdown]") {
  CHECK(markdown_text("N/m") == "N/m");
  CHECK(markdown_text("a|b") == "a\\|b");              // would split a table cell
  CHECK(markdown_text("[x](y) <b>*z*</b>") == "\\[x\\](y) \\<b\\>\\*z\\*\\</b\\>");
  CHECK(markdown_text("a\\b") == "a\\\\b");
  CHECK(markdown_text("line\nbreak") == "line\\\\x0Abreak");
}

TEST_CASE("code spans hold any text, backticks and pipes included", "[markdown]") {
  CHECK(markdown_code("data.csv") == "`data.csv`");
  CHECK(markdown_code("a`b") == "``a`b``");
  CHECK(markdown_code("`a") == "`` `a ``");
  CHECK(markdown_code("a|b") == "`a\\|b`");
  CHECK(markdown_code("a\nb") == "`a\\x0Ab`");
}
