#include "cli/parameter_roles.hpp"

#include <CLI/CLI.hpp>

#include <set>

#include "cli/commands.hpp"
#include "diagnosis/expr_build.hpp"
#include "diagnosis/text_patch.hpp"
#include "frontend/model_writer.hpp"
#include "frontend/parser.hpp"
#include "symbolic/to_ginac.hpp"

namespace mbgen::cli {

namespace {

ir::Parameter& parameter(ir::ModelIr& model, const std::string& option, const std::string& name) {
  for (ir::Parameter& p : model.parameters)
    if (p.name == name) {
      if (p.derived)
        throw CLI::ValidationError(option, "`" + name + "` is derived (an expression of other parameters): " +
                                               option + " the parameters it is built from");
      return p;
    }
  throw CLI::ValidationError(option, "the model has no parameter `" + name + "`");
}

// A bound: a decimal number, or inf / -inf for none.
std::optional<ir::Expr> bound_value(const std::string& text, const std::string& name, const std::string& which) {
  if (text == "inf" || text == "-inf" || text == "+inf") return std::nullopt;
  if (!symbolic::is_decimal_literal(text))
    throw CLI::ValidationError("--bound", name + ": the " + which + " bound `" + text +
                                              "` must be a decimal number such as 0, 1.5e6 or -2, or inf / -inf");
  if (const std::string problem = symbolic::decimal_limits_violation(text); !problem.empty())
    throw CLI::ValidationError("--bound", name + ": the " + which + " bound is out of range: " + problem);
  return diagnosis::num(text);
}

}  // namespace

void add_role_options(CLI::App& app, RoleOptions& roles) {
  app.add_option("--fix", roles.fix, "make an estimated parameter known: NAME, or NAME=VALUE at that value (repeatable)");
  app.add_option("--free", roles.free, "estimate a known or fixed parameter, within the model's bounds or --bound's "
                                       "(repeatable)");
  app.add_option("--bound", roles.bound, "an estimated parameter's bounds: NAME=LO:HI, inf or -inf for none "
                                         "(repeatable)");
}

namespace {

// Changes `model`'s roles and bounds as `roles` say (see read_model_with_roles).
void apply_role_options(const RoleOptions& roles, ir::ModelIr& model, std::map<std::string, std::string>& set) {
  std::set<std::string> named;
  const auto once = [&](const std::string& option, const std::string& name) {
    if (!named.insert(name).second)
      throw CLI::ValidationError(option, "`" + name + "` is named twice by --fix and --free");
  };
  for (const std::string& f : roles.fix) {
    const std::size_t eq = f.find('=');
    const std::string name = f.substr(0, eq);
    once("--fix", name);
    ir::Parameter& p = parameter(model, "--fix", name);
    if (p.role != ir::Role::Estimate)
      throw CLI::ValidationError("--fix", "`" + name + "` is not estimated (it is " + ir::to_string(p.role) +
                                              "); --set " + name + "=VALUE changes its value");
    p.role = ir::Role::Known;
    if (eq == std::string::npos) continue;
    std::map<std::string, std::string> value;
    try {
      value = parse_set_options({f});  // checked as --set's values are
    } catch (const CLI::ValidationError& e) {
      const std::string what = e.what(), prefix = "--set: ";
      throw CLI::ValidationError("--fix", what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
    }
    for (const auto& [n, v] : value)
      if (!set.emplace(n, v).second) throw CLI::ValidationError("--fix", n + " is given a value by --set and by --fix");
  }
  for (const std::string& name : roles.free) {
    once("--free", name);
    ir::Parameter& p = parameter(model, "--free", name);
    if (p.role == ir::Role::Estimate) throw CLI::ValidationError("--free", "`" + name + "` is already estimated");
    p.role = ir::Role::Estimate;
  }
  std::set<std::string> bounded;
  for (const std::string& b : roles.bound) {
    const std::size_t eq = b.find('='), colon = b.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos)
      throw CLI::ValidationError("--bound", "expected NAME=LO:HI, got `" + b + "`");
    const std::string name = b.substr(0, eq);
    if (!bounded.insert(name).second) throw CLI::ValidationError("--bound", "`" + name + "` is bounded twice");
    ir::Parameter& p = parameter(model, "--bound", name);
    if (p.role != ir::Role::Estimate)
      throw CLI::ValidationError("--bound", "`" + name + "` is not estimated: --free " + name + " estimates it");
    p.lower = bound_value(b.substr(eq + 1, colon - eq - 1), name, "lower");
    p.upper = bound_value(b.substr(colon + 1), name, "upper");
  }
}

}  // namespace

RoledModel read_model_with_roles(const std::string& path, const RoleOptions& roles,
                                 std::map<std::string, std::string>& set) {
  RoledModel out;
  out.text = frontend::read_model_text(path);
  out.model = frontend::parse_string(out.text, path);
  if (roles.empty()) return out;
  ir::ModelIr changed = out.model;
  apply_role_options(roles, changed, set);
  diagnosis::TextPatch patch(out.text, path);
  for (std::size_t i = 0; i < changed.parameters.size(); ++i) {
    ir::Parameter p = changed.parameters[i];
    const ir::Parameter& before = out.model.parameters[i];
    const auto text_of = [](const std::optional<ir::Expr>& e) { return e ? ir::to_string(*e) : std::string("-"); };
    if (p.role == before.role && text_of(p.lower) == text_of(before.lower) && text_of(p.upper) == text_of(before.upper))
      continue;
    p.comment.clear();  // the declaration's own comment stays where it is
    std::string line = frontend::write_parameter(p);
    line.pop_back();  // its newline: the statement is rewritten in place
    patch.rewrite_statement(before.loc, line);
  }
  out.text = patch.text();
  out.model = frontend::parse_string(out.text, path);
  return out;
}

}  // namespace mbgen::cli
