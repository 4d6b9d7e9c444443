#include "mbgen/data/data_settings.hpp"

#include <algorithm>

namespace mbgen {

namespace {
std::string join(const std::vector<std::string>& names) {
  if (names.empty()) return "(none)";
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}
}  // namespace

bool ChannelNames::is_input(const std::string& n) const {
  return std::find(inputs.begin(), inputs.end(), n) != inputs.end();
}

bool ChannelNames::is_output(const std::string& n) const {
  return std::find(outputs.begin(), outputs.end(), n) != outputs.end();
}

std::string ChannelNames::describe() const {
  return "inputs: " + join(inputs) + "; outputs: " + join(outputs);
}

}  // namespace mbgen
