// mbgen.read_data: a measured data file (CSV FRFs or time record, UFF 58/58b) read by the readers `fit` and `modal`
// use, as NumPy arrays with the channels' names; mbgen.write_data: such a dict written by `mbgen convert`'s writers.
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <mbgen/data/data_set.hpp>

#include <cmath>
#include <limits>

#include "bindings.hpp"
#include "cli/data_writing.hpp"
#include "cli/output_files.hpp"

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

SetMap set_map(const py::handle& set) {
  SetMap out;
  if (set.is_none()) return out;
  for (const auto& [name, value] : set.cast<py::dict>())
    out[py::str(name).cast<std::string>()] = {option_text(value), value.cast<double>(), 0};
  return out;
}

// A read_data dict (or one built alike) as the data set it describes; UsageError for a missing or misshapen entry.
DataSet data_set(const py::dict& d, const std::string& file) {
  const auto entry = [&](const char* key) {
    if (!d.contains(key)) usage_error("data", std::string("the dict has no '") + key + "' (as read_data returns)");
    return d[key];
  };
  const std::string kind = entry("kind").cast<std::string>();
  const py::object set = d.contains("set") ? py::object(d["set"]) : py::object(py::none());
  if (kind == "time") {
    TimeRecord record;
    record.file = file;
    record.set = set_map(set);
    record.t = entry("t").cast<Eigen::VectorXd>();
    const Eigen::MatrixXd values = entry("values").cast<Eigen::MatrixXd>();
    const auto names = entry("channels").cast<std::vector<std::string>>();
    if (values.rows() != record.t.size() || values.cols() != static_cast<Eigen::Index>(names.size()))
      usage_error("data", "values must be samples x channels");
    for (std::size_t s = 0; s < names.size(); ++s)
      record.signals.push_back({names[s], values.col(static_cast<Eigen::Index>(s))});
    if (d.contains("hold") && d["hold"].cast<std::string>() == "none") record.hold = HoldMode::None;
    return DataSet(std::move(record));
  }
  if (kind != "frf") usage_error("data", "kind must be 'frf' or 'time', got '" + kind + "'");
  FrfData frf;
  frf.file = file;
  frf.set = set_map(set);
  frf.f_hz = entry("f_hz").cast<Eigen::VectorXd>();
  const Eigen::MatrixXcd values = entry("values").cast<Eigen::MatrixXcd>();
  const auto outputs = entry("outputs").cast<std::vector<std::string>>();
  const auto inputs = entry("inputs").cast<std::vector<std::string>>();
  if (values.rows() != frf.f_hz.size() || values.cols() != static_cast<Eigen::Index>(outputs.size()) ||
      inputs.size() != outputs.size())
    usage_error("data", "values must be lines x channels, with an output and an input per channel");
  std::optional<Eigen::MatrixXd> coherence;
  if (d.contains("coherence") && !d["coherence"].is_none()) {
    coherence = d["coherence"].cast<Eigen::MatrixXd>();
    if (coherence->rows() != values.rows() || coherence->cols() != values.cols())
      usage_error("data", "coherence must be lines x channels, as values");
  }
  for (Eigen::Index c = 0; c < values.cols(); ++c) {
    FrfChannel ch{outputs[static_cast<std::size_t>(c)], inputs[static_cast<std::size_t>(c)], values.col(c),
                  std::nullopt};
    if (coherence && !coherence->col(c).array().isNaN().any()) ch.coherence = coherence->col(c);  // NaN: none
    frf.channels.push_back(std::move(ch));
  }
  return DataSet(std::move(frf));
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
  m.def(
      "write_data",
      [](const py::object& path, const py::dict& data, const py::object& model, const std::string& quantity) {
        const std::string file = path_text(path);
        const std::optional<cli::DataFormat> format = cli::data_format_of(file);
        if (!format) usage_error("path", "the name says the format: .uff or .unv (UFF 58) or .csv, got `" + file + "`");
        if (quantity != "auto" && quantity != "receptance" && quantity != "mobility" && quantity != "accelerance")
          usage_error("--quantity", "auto, receptance, mobility or accelerance, got `" + quantity + "`");
        if (quantity != "auto" && *format != cli::DataFormat::Uff)
          usage_error("--quantity", "only for a UFF output (CSV does not carry it)");
        cli::DataWriteRequest request;
        request.format = *format;
        request.quantity = quantity;
        request.title = "mbgen.write_data";
        if (!model.is_none()) {
          request.model_path = is_model(model) ? model_path(model) : path_text(model);
          if (is_model(model)) request.sets = model_options_of(model).sets;
        }
        const std::string origin = data.contains("file") ? data["file"].cast<std::string>() : file;
        const DataSet set = data_set(data, origin);
        released([&] {
          request.mappings = cli::own_mappings({origin});
          const cli::DataTexts texts = cli::data_texts(set, request);
          cli::OutputPlan plan;
          plan.files = {{"path", file}, {"path (its UFF mapping file)", *format == cli::DataFormat::Uff ? file + ".map" : ""}};
          plan.check();
          cli::OutputFiles out;
          out.add(file, texts.data);
          if (*format == cli::DataFormat::Uff) out.add(file + ".map", texts.mapping);
          out.commit();
        });
      },
      py::arg("path"), py::arg("data"), py::arg("model") = py::none(), py::arg("quantity") = "auto",
      "Writes a dict as read_data returns it, as `mbgen convert` writes data: PATH.csv (FRFs or a time record) or "
      "PATH.uff / PATH.unv (FRFs as ASCII UFF 58, with PATH.map beside it naming the points). model (a path or a "
      "mbgen.Model) gives the UFF points of its sensors and its outputs' quantity; quantity (UFF: receptance, "
      "mobility or accelerance) declares it. Whole or not at all.");
}

}  // namespace mbgen::python
