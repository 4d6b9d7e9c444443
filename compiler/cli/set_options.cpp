#include <CLI/CLI.hpp>

#include "cli/commands.hpp"
#include "ir/identifier.hpp"
#include "symbolic/to_ginac.hpp"

namespace mbgen::cli {

std::map<std::string, std::string> parse_set_options(const std::vector<std::string>& sets) {
  std::map<std::string, std::string> out;
  for (const std::string& s : sets) {
    const std::size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
      throw CLI::ValidationError("--set", "expected NAME=VALUE, got `" + s + "`");
    const std::string name = s.substr(0, eq), value = s.substr(eq + 1);
    if (!ir::is_identifier(name)) throw CLI::ValidationError("--set", "`" + name + "` is not a parameter name");
    if (!symbolic::is_decimal_literal(value))
      throw CLI::ValidationError("--set",
                                 name + "=" + value + ": the value must be a decimal number such as 1.5, -2 or 60e6");
    if (const std::string problem = symbolic::decimal_limits_violation(value); !problem.empty())
      throw CLI::ValidationError("--set", name + "=" + value + ": out of range: " + problem);
    if (!out.emplace(name, value).second) throw CLI::ValidationError("--set", name + " is set twice");
  }
  return out;
}

}  // namespace mbgen::cli
