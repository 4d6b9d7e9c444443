// Response records for output-only identification: the channels chosen, the records checked against each other.
#include "mbgen/data/data_error.hpp"
#include "mbgen/modal_identification/output_only_modal.hpp"

#include <algorithm>
#include <cmath>

namespace mbgen {

namespace {

constexpr double kSameDt = 1e-6;  // relative: records sampled alike

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

ResponseData response_data(const std::vector<TimeRecord>& records, const ResponseSelection& selection) {
  if (records.empty()) throw DataError("output-only modal analysis needs at least one time record");
  ResponseData data;
  const TimeRecord& first = records.front();
  for (const std::string& name : selection.ignore)
    if (!first.find(name)) throw DataError(first.file, 0, 0, "--ignore " + name + ": no such signal");
  for (const Signal& s : first.signals)
    if (!contains(selection.ignore, s.name)) data.channels.push_back(s.name);
  if (data.channels.empty()) throw DataError(first.file, 0, 0, "no response left after --ignore");
  if (!selection.ignore.empty()) data.notes.push_back("ignored (not responses): " + joined(selection.ignore));
  for (const std::string& name : selection.references) {
    const auto it = std::find(data.channels.begin(), data.channels.end(), name);
    if (it == data.channels.end())
      throw DataError(first.file, 0, 0, "reference " + name + " is not a response (" + joined(data.channels) + ")");
    const int index = static_cast<int>(it - data.channels.begin());
    if (std::find(data.references.begin(), data.references.end(), index) == data.references.end())
      data.references.push_back(index);
  }
  if (data.references.empty())
    for (std::size_t c = 0; c < data.channels.size(); ++c) data.references.push_back(static_cast<int>(c));
  data.dt = first.dt();
  for (const TimeRecord& r : records) {
    data.files.push_back(r.file);
    std::vector<std::string> names;
    for (const Signal& s : r.signals)
      if (!contains(selection.ignore, s.name)) names.push_back(s.name);
    if (names != data.channels)
      throw DataError(r.file, 0, 0, "its responses (" + joined(names) + ") differ from " + first.file + "'s (" +
                                        joined(data.channels) + "); records of several setups are not merged");
    if (r.samples() < kMinResponseSamples)
      throw DataError(r.file, 0, 0, "too short for output-only modal analysis: " + std::to_string(r.samples()) +
                                        " samples, at least " + std::to_string(kMinResponseSamples) + " needed");
    if (std::abs(r.dt() - data.dt) > kSameDt * data.dt)
      throw DataError(r.file, 0, 0, "sampled at dt = " + std::to_string(r.dt()) + " s, " + first.file + " at " +
                                        std::to_string(data.dt) + " s");
    Eigen::MatrixXd y(r.samples(), static_cast<Eigen::Index>(names.size()));
    for (std::size_t c = 0; c < names.size(); ++c) {
      const Eigen::VectorXd& v = r.at(names[c]).values;
      if (!v.allFinite()) throw DataError(r.file, 0, 0, "signal " + names[c] + " has a non-finite sample");
      // Operational responses are fluctuations about a static offset (a sensor's bias, gravity): removed.
      y.col(static_cast<Eigen::Index>(c)) = v.array() - v.mean();
      if (y.col(static_cast<Eigen::Index>(c)).squaredNorm() <= 0)
        throw DataError(r.file, 0, 0, "signal " + names[c] + " is constant");
    }
    data.records.push_back(std::move(y));
  }
  return data;
}

}  // namespace mbgen
