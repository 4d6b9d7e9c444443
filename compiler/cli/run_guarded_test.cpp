#include "cli/run_guarded.hpp"

#include <catch2/catch.hpp>

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
