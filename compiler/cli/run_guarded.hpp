// Runs a command body, turning exceptions into messages and exit statuses: bad input (a model or data error,
// any std::exception from the pipeline) is status 1; usage errors (CLI11) are status 2.
#pragma once

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

namespace mbgen::cli {

template <typename Body>
int run_guarded(CLI::App& app, int argc, char** argv, Body body) {
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
    return 2;
  }
  try {
    return body();
  } catch (const CLI::ParseError& e) {  // usage problems found after parsing (e.g. a malformed --set)
    std::cerr << "mbgen: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}

}  // namespace mbgen::cli
