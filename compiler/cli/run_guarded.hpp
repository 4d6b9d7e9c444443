// Runs a command body, turning exceptions into messages and exit statuses (docs/cli.md):
//   1  bad input: a model, data or output error (their messages name the file, and line and column where known),
//      or not enough memory for the input;
//   2  bad usage (CLI11, and option values checked after parsing);
//   3  an internal error: any other exception is a bug in mbgen, reported as such.
#pragma once

#include <CLI/CLI.hpp>
#include <mbgen/data/data_error.hpp>
#include <mbgen/dynamics/dynamics_error.hpp>
#include <mbgen/estimation/fit.hpp>

#include <exception>
#include <iostream>
#include <new>

#include "cli/output_files.hpp"
#include "frontend/diagnostics.hpp"

namespace mbgen::cli {

inline constexpr int kExitBadInput = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInternal = 3;

// A message as the user sees it: those that name a file carry `FILE[:LINE:COLUMN]: error:` already; the others (a
// method's refusal, "fit: --method arx-two-stage needs the mass matrix known ...") get `mbgen: error:`.
inline std::string error_message(const std::string& what) {
  if (what.find(": error: ") != std::string::npos || what.rfind("mbgen: ", 0) == 0) return what;
  return "mbgen: error: " + (what.rfind("fit: ", 0) == 0 ? what.substr(5) : what);
}

// Inside a catch block: prints the exception in flight as run_guarded does and returns its exit status.
inline int report_current_exception() {
  try {
    throw;
  } catch (const CLI::ParseError& e) {  // usage problems found after parsing (e.g. a malformed --set)
    std::cerr << "mbgen: " << e.what() << "\n";
    return kExitUsage;
  } catch (const frontend::ModelError& e) {
    std::cerr << e.what() << "\n";
  } catch (const DataError& e) {
    std::cerr << e.what() << "\n";
  } catch (const FitError& e) {
    std::cerr << error_message(e.what()) << "\n";
  } catch (const DynamicsError& e) {
    std::cerr << error_message(e.what()) << "\n";
  } catch (const OutputError& e) {
    std::cerr << e.what() << "\n";
  } catch (const std::bad_alloc&) {
    std::cerr << "mbgen: error: out of memory: the input is too large for this machine (docs/limits.md)\n";
  } catch (const std::exception& e) {
    std::cerr << "mbgen: internal error: " << e.what()
              << "\nThis is a bug in mbgen, not a problem with the input; please report it with the command line and "
                 "its input files.\n";
    return kExitInternal;
  } catch (...) {
    std::cerr << "mbgen: internal error: an exception of unknown type\nThis is a bug in mbgen; please report it.\n";
    return kExitInternal;
  }
  return kExitBadInput;
}

// An option or argument given an empty value (`--report ''`, `-o ''`) names nothing. Taking it for "not given" would
// silently skip an output the user asked for (or, for -o, fail after writing the header): a usage error instead.
inline void refuse_empty_values(const CLI::App& app) {
  for (const CLI::Option* option : app.get_options())
    if (option->get_type_size() > 0)
      for (const std::string& value : option->results())
        if (value.empty()) throw CLI::ValidationError(option->get_name(), "an empty value names nothing");
}

// `model_file` (when given and, after parsing, not empty) names the model the command analyses: the numeric
// dynamics failing on it (a singular dynamic stiffness, a state matrix that overflows a double) is a problem of
// that model's values, and the message names it.
template <typename Body>
int run_guarded(CLI::App& app, int argc, char** argv, Body body, const std::string* model_file = nullptr) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << "mbgen: " << e.what() << "\nRun with --help for usage.\n";
    return kExitUsage;
  }
  try {
    refuse_empty_values(app);
    return body();
  } catch (const DynamicsError& e) {
    if (!model_file || model_file->empty()) return report_current_exception();
    std::cerr << frontend::ModelError(*model_file, {}, e.what()).what() << "\n";
    return kExitBadInput;
  } catch (...) {
    return report_current_exception();
  }
}

}  // namespace mbgen::cli
