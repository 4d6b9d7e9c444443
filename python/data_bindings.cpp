// mbgen.read_data: a measured data file (CSV FRFs or time record, UFF 58/58b) read by the readers `fit` and `modal`
// use, as NumPy arrays with the channels' names.
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <mbgen/data/data_set.hpp>

#include <limits>

#include "bindings.hpp"

namespace mbgen::python {

namespace {

py::dict set_values(const SetMap& set) {
  py::dict out;
  for (const auto& [name, value] : set) out[py::str(name)] = value.value;
  return out;
}

py::dict frf_dict(const FrfData& frf) {
  const Eigen::Index lines = frf.f_hz.size(), channels = static_cast<Eigen::Index>(frf.channels.size());
  Eigen::MatrixXcd values(lines, channels);
  Eigen::MatrixXd coherence = Eigen::MatrixXd::Constant(lines, channels, std::numeric_limits<double>::quiet_NaN());
  bool any_coherence = false;
  std::vector<std::string> names, outputs, inputs;
  for (Eigen::Index c = 0; c < channels; ++c) {
    const FrfChannel& ch = frf.channels[static_cast<std::size_t>(c)];
    values.col(c) = ch.values;
    if (ch.coherence) coherence.col(c) = *ch.coherence, any_coherence = true;
    names.push_back(ch.output + "/" + ch.input);
    outputs.push_back(ch.output);
    inputs.push_back(ch.input);
  }
  py::dict d;
  d["kind"] = "frf";
  d["file"] = frf.file;
  d["f_hz"] = frf.f_hz;
  d["values"] = values;  // lines x channels
  d["channels"] = names, d["outputs"] = outputs, d["inputs"] = inputs;
  // NaN for a channel without coherence; None when none has any.
  d["coherence"] = any_coherence ? py::cast(coherence) : py::none();
  d["set"] = set_values(frf.set);
  return d;
}

py::dict time_dict(const TimeRecord& record) {
  const Eigen::Index samples = record.samples(), signals = static_cast<Eigen::Index>(record.signals.size());
  Eigen::MatrixXd values(samples, signals);
  std::vector<std::string> names;
  for (Eigen::Index s = 0; s < signals; ++s) {
    values.col(s) = record.signals[static_cast<std::size_t>(s)].values;
    names.push_back(record.signals[static_cast<std::size_t>(s)].name);
  }
  py::dict d;
  d["kind"] = "time";
  d["file"] = record.file;
  d["t"] = record.t;
  d["values"] = values;  // samples x signals
  d["channels"] = names;
  d["hold"] = record.hold == HoldMode::None ? "none" : "zero-order";
  d["set"] = set_values(record.set);
  return d;
}

}  // namespace

void register_data(py::module_& m) {
  m.def(
      "read_data",
      [](const py::object& path) {
        const std::string file = path_text(path);
        const DataSet data = released([&] { return read_data_file(file); });
        return data.is_frf() ? frf_dict(std::get<FrfData>(data.content)) : time_dict(std::get<TimeRecord>(data.content));
      },
      py::arg("path"),
      "Reads a data file as mbgen does (CSV FRFs or time record, UFF 58/58b with PATH.map beside it): a dict with "
      "kind ('frf' or 'time'), f_hz or t, values (lines x channels, complex; or samples x signals), channels, set, "
      "and coherence (FRFs) or hold (records).");
}

}  // namespace mbgen::python
