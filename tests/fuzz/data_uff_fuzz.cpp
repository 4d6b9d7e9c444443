// Fuzz target: a UFF 58/58b file (ASCII or binary) through the reader `mbgen fit --data` uses, without a channel
// mapping (default names). Bad input must end in DataError; anything else is a bug.
#include <mbgen/data/data_error.hpp>
#include <mbgen/data/data_set.hpp>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    mbgen::read_data(in, "fuzz.uff");
  } catch (const mbgen::DataError&) {
  }
  return 0;
}
