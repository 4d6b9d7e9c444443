#include "cli/run_guarded.hpp"

#include <catch2/catch.hpp>

#include <iostream>
#include <sstream>
#include <stdexcept>

using namespace mbgen;

namespace {

// The exit status run_guarded gives a body that throws `e`.
template <typename E>
int status_for(const E& e) {
  CLI::App app{"test"};
  char name[] = "mbgen";
  char* argv[] = {name};
  return cli::run_guarded(app, 1, argv, [&]() -> int { throw e; });
}

}  // namespace

TEST_CASE("exit statuses: bad input 1, usage 2, internal errors 3", "[cli]") {
  CHECK(status_for(frontend::ModelError("m.mdl", {1, 2}, "bad")) == 1);
  CHECK(status_for(DataError("d.csv", 3, 1, "bad")) == 1);
  CHECK(status_for(FitError("bad")) == 1);
  CHECK(status_for(cli::OutputError("out: cannot write")) == 1);
  CHECK(status_for(std::bad_alloc()) == 1);
  CHECK(status_for(CLI::ValidationError("--set", "bad")) == 2);
  // Anything else is a bug in mbgen, not bad input.
  CHECK(status_for(std::logic_error("invariant")) == 3);
  CHECK(status_for(std::runtime_error("unexpected")) == 3);
  CHECK(status_for(std::invalid_argument("unexpected")) == 3);
}

TEST_CASE("a failure of the numeric dynamics names the command's model, and an empty option value is usage", "[cli]") {
  CLI::App app{"test"};
  std::string model = "m.mdl", report;
  app.add_option("model", model);
  app.add_option("--report", report);
  std::ostringstream err;
  std::streambuf* const saved = std::cerr.rdbuf(err.rdbuf());
  char name[] = "mbgen", model_arg[] = "m.mdl", report_option[] = "--report", empty[] = "";
  char* argv[] = {name, model_arg};
  const int dynamics =
      cli::run_guarded(app, 2, argv, []() -> int { throw DynamicsError("M^-1 K overflows a double"); }, &model);
  const std::string dynamics_message = err.str();
  err.str("");
  char* argv_empty[] = {name, model_arg, report_option, empty};
  CLI::App app2{"test"};
  app2.add_option("model", model);
  app2.add_option("--report", report);
  const int usage = cli::run_guarded(app2, 4, argv_empty, []() -> int { return 0; });
  std::cerr.rdbuf(saved);
  CHECK(dynamics == 1);
  CHECK(dynamics_message == "m.mdl: error: M^-1 K overflows a double\n");
  CHECK(usage == 2);
  CHECK(err.str() == "mbgen: --report: an empty value names nothing\n");
}
