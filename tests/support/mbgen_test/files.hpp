// The repository's files and a scratch directory, for tests: examples found by name, whole files read, and a
// directory per test under the build tree. Header-only; include from *_test.cpp files only (they are compiled with
// mbgen_source_dir() and mbgen_binary_dir(), CMakeLists.txt: mbgen_add_tests).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include "mbgen_test/paths.hpp"

namespace mbgen::test {

// A file of the source tree by its path relative to the root, e.g. "examples/mdof2/data/frf_F1.csv".
inline std::string source_path(const std::string& relative) { return std::string(mbgen_source_dir()) + "/" + relative; }

// examples/NAME/NAME.mdl.
inline std::string example_model_path(const std::string& name) {
  return source_path("examples/" + name + "/" + name + ".mdl");
}

// The whole of a file; std::runtime_error if it cannot be read.
inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::string example_model_text(const std::string& name) { return read_text(example_model_path(name)); }

// BUILD/test-tmp/NAME, created if missing (its contents are the test's to manage).
inline std::filesystem::path test_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(mbgen_binary_dir()) / "test-tmp" / name;
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace mbgen::test
