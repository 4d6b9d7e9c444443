#include <CLI/CLI.hpp>

#include "cli/commands.hpp"

namespace mbgen::cli {

std::map<std::string, std::string> parse_set_options(const std::vector<std::string>& sets) {
  std::map<std::string, std::string> out;
  for (const std::string& s : sets) {
    const std::size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
      throw CLI::ValidationError("--set", "expected NAME=VALUE, got `" + s + "`");
    out[s.substr(0, eq)] = s.substr(eq + 1);
  }
  return out;
}

}  // namespace mbgen::cli
