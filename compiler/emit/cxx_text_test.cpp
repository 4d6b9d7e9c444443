#include "emit/cxx_text.hpp"

#include <catch2/catch.hpp>

using namespace mbgen::emit;

TEST_CASE("string literals escape quotes, backslashes, trigraphs and control bytes", "[emit][cxx_text]") {
  CHECK(cxx_string_literal("N/m") == "\"N/m\"");
  CHECK(cxx_string_literal("a\"b\\c") == "\"a\\\"b\\\\c\"");
  // `?` "?=" and the like: written apart here so that this file holds no trigraph itself.
  CHECK(cxx_string_literal("?" "?=") == "\"\\?\\?=\"");  // no trigraph under -trigraphs
  CHECK(cxx_string_literal("a\nb") == "\"a\\012b\"");
  CHECK(cxx_string_literal("\x01" "7") == "\"\\0017\"");          // three octal digits: the 7 stays a character
  CHECK(cxx_string_literal("\xC3\xA9") == "\"\\303\\251\"");
}

TEST_CASE("comment text cannot end the line or splice the next one onto it", "[emit][cxx_text]") {
  CHECK(cxx_comment_text("spindle.mdl") == "spindle.mdl");
  CHECK(cxx_comment_text("a\nstatic int x;") == "a\\x0Astatic int x;");
  CHECK(cxx_comment_text("a\\") == "a\\x5C");     // a backslash at the end of a // comment continues it
  CHECK(cxx_comment_text("a?" "?/") == "a\\x3F\\x3F/");
  CHECK(cxx_comment_text("Pr\xC3\xBC" "fstand") == "Pr\xC3\xBC" "fstand");  // valid UTF-8 stays readable
  CHECK(cxx_comment_text("\xFF") == "\\xFF");
}

TEST_CASE("header names that #include \"...\" cannot hold are named", "[emit][cxx_text]") {
  CHECK(include_name_problem("spindle_model.hpp").empty());
  CHECK_FALSE(include_name_problem("a\"b.hpp").empty());
  CHECK_FALSE(include_name_problem("a\\b.hpp").empty());
  CHECK_FALSE(include_name_problem("a\nb.hpp").empty());
  CHECK_FALSE(include_name_problem("a?" "?/b.hpp").empty());
  CHECK_FALSE(include_name_problem("").empty());
}

TEST_CASE("namespaces: identifiers, not keywords, reserved names or namespaces the code uses", "[emit][cxx_text]") {
  CHECK(namespace_problem("mbgen_models::spindle").empty());
  CHECK(namespace_problem("a::b::c").empty());
  for (const char* bad : {"namespace", "int", "class::new", "mbgen_models::std", "Eigen", "mbgen", "a::mpfr",
                          "linux", "a b", "a::", "::a", "a:::b", "__x", "_X", "", "3d"}) {
    INFO(bad);
    CHECK_FALSE(namespace_problem(bad).empty());
  }
}
