#include "mbgen/data/time_record.hpp"

#include "mbgen/data/data_error.hpp"

namespace mbgen {

double TimeRecord::dt() const {
  if (t.size() < 2) throw DataError(file, 0, 0, "a time record needs at least 2 samples for a sample interval");
  return (t[t.size() - 1] - t[0]) / static_cast<double>(t.size() - 1);
}

const Signal* TimeRecord::find(const std::string& name) const {
  for (const auto& s : signals)
    if (s.name == name) return &s;
  return nullptr;
}

const Signal& TimeRecord::at(const std::string& name) const {
  if (const Signal* s = find(name)) return *s;
  std::string have;
  for (const auto& s : signals) have += (have.empty() ? "" : ", ") + s.name;
  throw DataError(file, 0, 0, "time record has no signal '" + name + "' (it has: " + have + ")");
}

void require_inputs(const TimeRecord& record, const std::vector<std::string>& inputs) {
  std::string missing;
  for (const auto& n : inputs)
    if (!record.find(n)) missing += (missing.empty() ? "" : ", ") + n;
  if (!missing.empty())
    throw DataError(record.file, 0, 0, "time record lacks model input(s) " + missing +
                                           ": a simulation needs every input");
}

}  // namespace mbgen
