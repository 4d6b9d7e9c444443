// The subcommands of `mbgen`. Each parses its own arguments (CLI11) and returns the exit status:
// 0 success, 1 bad input (model, data), 2 bad usage.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace mbgen::cli {

int run_compile(int argc, char** argv);
int run_inspect(int argc, char** argv);
int run_fit(int argc, char** argv);
int run_diagnose(int argc, char** argv);
int run_modal(int argc, char** argv);
int run_sensitivity(int argc, char** argv);
int run_monitor(int argc, char** argv);
int run_export(int argc, char** argv);
int run_convert(int argc, char** argv);

// `--set NAME=VALUE` options, checked for form (the symbolic stage checks the names and values).
std::map<std::string, std::string> parse_set_options(const std::vector<std::string>& sets);

}  // namespace mbgen::cli
