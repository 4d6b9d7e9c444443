// Fuzz target: a UFF file through the readers of modes (dataset 55) and nodes (dataset 15), which skip every other
// dataset (58b by its byte count). Bad input must end in DataError; anything else is a bug.
#include <mbgen/data/data_error.hpp>
#include <mbgen/data/uff55.hpp>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    std::istringstream in(text);
    mbgen::read_uff55(in, "fuzz.uff");
  } catch (const mbgen::DataError&) {
  }
  try {
    std::istringstream in(text);
    mbgen::read_uff15(in, "fuzz.uff");
  } catch (const mbgen::DataError&) {
  }
  return 0;
}
