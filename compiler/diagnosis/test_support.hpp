// Helpers shared by the diagnosis tests: the examples with their text, and the checks every candidate must pass.
#pragma once

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "diagnosis/extension.hpp"
#include "frontend/model_writer.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/test_support.hpp"
#include "mbgen_test/paths.hpp"

namespace mbgen::diagnosis::test {

struct Example {
  std::string text;
  ir::ModelIr model;
};

inline Example load(const std::string& name) {
  const std::string path = std::string(mbgen_source_dir()) + "/examples/" + name + "/" + name + ".mdl";
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return {text.str(), frontend::parse_string(text.str(), path)};
}

inline std::vector<std::string> ids_of(const std::vector<Extension>& xs) {
  std::vector<std::string> out;
  for (const Extension& x : xs) out.push_back(x.id);
  return out;
}

// The ids of the structural candidates (the measurement chain's left out: every model gets them, enumerate_test checks
// them on their own).
inline std::vector<std::string> structural_ids_of(const std::vector<Extension>& xs) {
  std::vector<std::string> out;
  for (const Extension& x : xs)
    if (x.operator_name != "measurement_chain") out.push_back(x.id);
  return out;
}

inline const Extension& find(const std::vector<Extension>& xs, const std::string& id) {
  for (const Extension& x : xs)
    if (x.id == id) return x;
  FAIL("no candidate " << id);
  throw std::logic_error("unreachable");
}

// The text parses to the model; the model derives with a non-singular mass matrix at the start values.
inline symbolic::SymbolicModel check_candidate(const Extension& x) {
  INFO(x.id << "\n" << x.mdl_text);
  CHECK(x.id == x.operator_name + ":" + x.target);
  CHECK(x.mdl_text.find("# --- mbgen diagnose: " + x.id + ": " + x.description + " ---\n") != std::string::npos);
  const ir::ModelIr parsed = frontend::parse_string(x.mdl_text, "extended.mdl");
  CHECK(frontend::write_model(parsed) == frontend::write_model(x.model));
  for (const NewParameter& p : x.new_parameters) {
    const ir::Parameter* q = x.model.find_parameter(p.name);
    REQUIRE(q);
    CHECK(q->role == ir::Role::Estimate);
    CHECK_FALSE(p.why.empty());
  }
  for (const std::string& name : x.freed_parameters) CHECK(x.model.find_parameter(name)->role == ir::Role::Estimate);
  symbolic::DeriveOptions options;
  options.transfer_functions = false;
  symbolic::SymbolicModel sm = symbolic::derive(x.model, options);
  const Eigen::MatrixXd M = symbolic::test::to_eigen(sm.M, sm.values());
  CHECK(M.rows() > 0);
  CHECK(std::abs(M.determinant()) > 0);
  // The text describes the model numerically too: the written form leaves out what it takes as implied (a point
  // that is its body's centre of mass), so equal written forms alone can hide a point the text lost.
  const symbolic::SymbolicModel from_text = symbolic::derive(parsed, options);
  const auto same = [&](const auto& a, const auto& b) {
    const Eigen::MatrixXd x = symbolic::test::to_eigen(a, sm.values()), y = symbolic::test::to_eigen(b, from_text.values());
    return x.rows() == y.rows() && x.cols() == y.cols() && (x - y).norm() <= 1e-12 * (1 + x.norm());
  };
  CHECK(same(sm.M, from_text.M));
  CHECK(same(sm.C, from_text.C));
  CHECK(same(sm.K, from_text.K));
  return sm;
}

}  // namespace mbgen::diagnosis::test
