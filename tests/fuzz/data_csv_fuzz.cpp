// Fuzz target: a CSV data file (time record or FRFs, by its header) through the reader `mbgen fit --data` uses.
// Bad input must end in DataError; anything else is a bug.
#include <mbgen/data/data_error.hpp>
#include <mbgen/data/data_set.hpp>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    mbgen::read_data(in, "fuzz.csv", mbgen::ChannelNames{{"F1", "F2"}, {"d1", "d2"}});
  } catch (const mbgen::DataError&) {
  }
  return 0;
}
