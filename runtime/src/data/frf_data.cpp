#include "mbgen/frf_data.hpp"

namespace mbgen {

const FrfChannel* FrfData::find(const std::string& output, const std::string& input) const {
  for (const auto& c : channels)
    if (c.output == output && c.input == input) return &c;
  return nullptr;
}

}  // namespace mbgen
