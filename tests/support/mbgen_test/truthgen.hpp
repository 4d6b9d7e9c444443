// For the estimators' tests: a data set made by the independent truth generator (scripts/truthgen: numpy, its own
// model assembly and simulation) and its truth parameters (from the .truth.json beside it, for the comparison only).
// Test-only header (Catch2).
#pragma once

#include "mbgen_test/files.hpp"

#include "mbgen/data/data_set.hpp"
#include "mbgen/estimation/fit.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include "mbgen_test/paths.hpp"

namespace mbgen::test {

struct TruthgenData {
  DataSet data;
  std::map<std::string, double> truth;
};

// Runs `truthgen.py ARGUMENTS -o BUILD/DIR/STEM.csv` and reads what it wrote.
inline TruthgenData truthgen_data(const std::string& arguments, const std::string& dir, const std::string& stem) {
  const std::filesystem::path folder = std::filesystem::path(mbgen_binary_dir()) / dir;
  std::filesystem::create_directories(folder);
  const std::string path = (folder / stem).string();
  const std::string command =
      "/usr/bin/python3 " + source_path("scripts/truthgen/truthgen.py") + " " + arguments + " -o " + path + ".csv";
  REQUIRE(std::system(command.c_str()) == 0);
  TruthgenData g{read_data_file(path + ".csv"), {}};
  std::ifstream in(path + ".truth.json");
  const nlohmann::json parameters = nlohmann::json::parse(in).at("parameters");
  for (auto it = parameters.begin(); it != parameters.end(); ++it) g.truth[it.key()] = it.value().get<double>();
  return g;
}

}  // namespace mbgen::test
