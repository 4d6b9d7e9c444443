#include "frontend/message.hpp"

#include <catch2/catch.hpp>

#include "frontend/diagnostics.hpp"

using namespace mbgen;

TEST_CASE("error messages: one form, located where a place is known, formatted by fmt") {
  CHECK(frontend::error_text("m.mdl", ir::SourceLoc{3, 7}, "unknown body `{}`", "b2") ==
        "m.mdl:3:7: error: unknown body `b2`");
  CHECK(frontend::error_text("out", "cannot write: {}", "it is a directory") ==
        "out: error: cannot write: it is a directory");
  CHECK(frontend::error_text("", ir::SourceLoc{}, std::string_view("no file")) == "<model>: error: no file");
  const frontend::ModelError e("m.mdl", ir::SourceLoc{2, 1}, "`{}` is reserved and cannot name a parameter", "pi");
  CHECK(std::string(e.what()) == "m.mdl:2:1: error: `pi` is reserved and cannot name a parameter");
  CHECK(e.message() == "`pi` is reserved and cannot name a parameter");
}
