// `--fix NAME[=VALUE]`, `--free NAME` and `--bound NAME=LO:HI`: a parameter's role changed for one run without
// editing the model file (docs/cli.md, "Parameter roles"). `fit`, `diagnose`, `monitor` and `sensitivity` take them.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ir/model_ir.hpp"

namespace CLI {
class App;
}

namespace mbgen::cli {

struct RoleOptions {
  std::vector<std::string> fix;    // NAME or NAME=VALUE: an estimated parameter becomes known (at VALUE)
  std::vector<std::string> free;   // NAME: a known or fixed parameter is estimated
  std::vector<std::string> bound;  // NAME=LO:HI: an estimated parameter's bounds (inf, -inf for none)
  bool empty() const { return fix.empty() && free.empty() && bound.empty(); }
};

void add_role_options(CLI::App& app, RoleOptions& roles);

// A model with the roles changed: its text with each changed parameter's declaration rewritten in place (the
// lines keep their numbers, so messages point into the file as written), and the model parsed from that text.
struct RoledModel {
  std::string text;
  ir::ModelIr model;
};

// Reads the model at `path` ("-": standard input) and applies `roles`, adding --fix's values to `set` (the --set
// overrides). Throws CLI::ValidationError (status 2) naming the option for a malformed option, an unknown or derived
// parameter, a role the option cannot change (--fix of a known parameter, --free of an estimated one), a parameter
// named twice, and a value both --set and --fix give.
RoledModel read_model_with_roles(const std::string& path, const RoleOptions& roles,
                                 std::map<std::string, std::string>& set);

}  // namespace mbgen::cli
