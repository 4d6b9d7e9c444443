#include "ir/identifier.hpp"

#include <catch2/catch.hpp>

using namespace mbgen::ir;

TEST_CASE("identifiers of the language, and the one sanitizer that makes them from file names") {
  CHECK(is_identifier("m1"));
  CHECK(is_identifier("_x"));
  CHECK_FALSE(is_identifier(""));
  CHECK_FALSE(is_identifier("1m"));
  CHECK_FALSE(is_identifier("a b"));
  CHECK(to_identifier("my-model v2") == "my_model_v2");
  CHECK(to_identifier("2dof") == "m_2dof");
  CHECK(to_identifier("") == "m_");
  CHECK(to_identifier("\xC3\xA9t\xC3\xA9") == "__t__");  // every byte of a UTF-8 letter becomes `_`
  CHECK(cxx_parameter_variable("k_fx") == "p_k_fx");
}

TEST_CASE("reserved names and words of the language") {
  CHECK(is_reserved_name("pi"));
  CHECK(is_reserved_name("inf"));
  CHECK_FALSE(is_reserved_name("x"));
  CHECK(is_language_word("x"));
  CHECK(is_language_word("estimate"));
  CHECK_FALSE(is_language_word("pi"));
  CHECK_FALSE(is_language_word("mass1"));
}

TEST_CASE("which user names cannot name something the generated C++ declares") {
  CHECK(cxx_identifier_problem("spindle").empty());
  CHECK(cxx_identifier_problem("int") == "`int` is a C++ keyword or a predefined macro");
  CHECK(cxx_identifier_problem("linux") == "`linux` is a C++ keyword or a predefined macro");
  CHECK(cxx_identifier_problem("Eigen") == "`Eigen` would hide the namespace `Eigen` that the generated code uses");
  CHECK(cxx_identifier_problem("a__b").find("reserved") != std::string::npos);
  CHECK(cxx_identifier_problem("_Model").find("reserved") != std::string::npos);
  CHECK(cxx_identifier_problem("a b") == "`a b` is not an identifier (letters, digits and _)");
  CHECK(cxx_identifier_problem("") == "a part of it is empty");
}
