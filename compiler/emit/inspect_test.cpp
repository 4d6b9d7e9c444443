#include "emit/inspect.hpp"

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <regex>

#include "emit/test_mdof2.hpp"

using namespace mbgen::emit;

TEST_CASE("JSON inspection follows mbgen-inspect/1") {
  test::Mdof2 a;
  const std::string text = emit_inspect(a.sm, InspectFormat::Json);
  CHECK(text == emit_inspect(a.sm, InspectFormat::Json));
  const auto j = nlohmann::ordered_json::parse(text);
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  CHECK(keys == std::vector<std::string>{"schema", "parameters", "coordinates", "inputs", "outputs", "M", "C", "K",
                                         "transfer_functions", "modes"});
  CHECK(j["schema"] == "mbgen-inspect/1");
  CHECK(j["parameters"][0]["name"] == "m1");
  CHECK(j["parameters"][0]["value"] == 1.39);
  CHECK(j["parameters"][0]["role"] == "known");
  CHECK(j["coordinates"].get<std::vector<std::string>>() == std::vector<std::string>{"mass1.x", "mass2.x"});
  CHECK(j["M"][0][0] == "m1");
  CHECK(j["M"][0][1] == "0");
  CHECK(j["K"][0][1] == "-k12");
  const auto& g11 = j["transfer_functions"][0];
  CHECK(g11["symbolic"] == true);
  CHECK(g11["numerator"][2] == "1/m1");
  CHECK(g11["denominator"].back() == "1");
  // Every expression string uses only names, integers, + - * / ^, parentheses and spaces.
  const std::regex allowed("[A-Za-z_0-9+\\-*/^() ]+");
  for (const char* m : {"M", "C", "K"})
    for (const auto& row : j[m])
      for (const auto& e : row) CHECK(std::regex_match(e.get<std::string>(), allowed));
  for (const auto& tf : j["transfer_functions"])
    for (const char* part : {"numerator", "denominator"})
      for (const auto& e : tf[part]) CHECK(std::regex_match(e.get<std::string>(), allowed));
  // Modes of Table 5.1 values (docs/reference-models.md): 89.72 Hz (zeta 0.000514), 166.29 Hz (zeta 0.00455).
  REQUIRE(j["modes"].size() == 2);
  CHECK(j["modes"][0]["f_hz"].get<double>() == Approx(89.72).epsilon(1e-4));
  CHECK(j["modes"][0]["zeta"].get<double>() == Approx(0.000514).epsilon(1e-2));
  CHECK(j["modes"][1]["f_hz"].get<double>() == Approx(166.29).epsilon(1e-4));
  CHECK(j["modes"][1]["zeta"].get<double>() == Approx(0.00455).epsilon(1e-2));
}

TEST_CASE("markdown and latex inspection are deterministic and complete") {
  test::Mdof2 a;
  const std::string md = emit_inspect(a.sm, InspectFormat::Markdown);
  CHECK(md == emit_inspect(a.sm, InspectFormat::Markdown));
  CHECK(md.find("### Mass matrix M") != std::string::npos);
  CHECK(md.find("- b2 = `1/m1`") != std::string::npos);
  CHECK(md.find("Gyroscopic") == std::string::npos);  // no spin
  const std::string tex = emit_inspect(a.sm, InspectFormat::Latex);
  CHECK(tex == emit_inspect(a.sm, InspectFormat::Latex));
  CHECK(tex.find("\\begin{bmatrix}") != std::string::npos);
  CHECK(tex.find("k12") != std::string::npos);
  CHECK(tex.find("\\end{document}") != std::string::npos);
  CHECK_THROWS_AS(parse_inspect_format("yaml"), std::invalid_argument);
  CHECK(parse_inspect_format("latex") == InspectFormat::Latex);
}
