// Fuzz target: model text -> parser, checks, and the exact values of every parameter and bound (the number limits
// of docs/limits.md). Bad input must end in frontend::ModelError; anything else (a crash, a sanitizer report, another
// exception, a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"
#include "symbolic/to_ginac.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const mbgen::ir::ModelIr model = mbgen::frontend::parse_string(text, "fuzz.mdl");
    const mbgen::symbolic::ParameterTable table(model);
    for (const mbgen::ir::Parameter& p : model.parameters) {
      table.convert(p.value);
      if (p.lower) table.convert(*p.lower);
      if (p.upper) table.convert(*p.upper);
    }
  } catch (const mbgen::frontend::ModelError&) {
  }
  return 0;
}
