// `mbgen export MODEL.mdl [--what matrices|state-space|modes|frf] [--frf LO:HI:N] [--format json|csv|uff|mat]
// [--fit-result FIT.json] [--set ...] [-o OUT]`: the model's numbers at its values or at an estimate, for another
// tool (docs/interfaces.md, "mbgen-export/1"). Deterministic: the same input gives the same bytes.
#include <mbgen/data/csv.hpp>
#include <mbgen/data/data_error.hpp>
#include <mbgen/dynamics/frf.hpp>
#include <mbgen/dynamics/model_modes.hpp>
#include <mbgen/dynamics/state_space.hpp>
#include <mbgen/data/uff.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/command_runs.hpp"
#include "cli/commands.hpp"
#include "cli/export_mat.hpp"
#include "cli/mat_file.hpp"
#include "cli/output_files.hpp"
#include "cli/run_guarded.hpp"
#include "cli/uff_modes.hpp"
#include "cli/version.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"

namespace mbgen::cli {

namespace {

using Json = nlohmann::json;  // keys sorted, as every mbgen JSON but inspect's and diagnose's (docs/interfaces.md)

Json matrix_json(const Eigen::MatrixXd& m) {
  Json rows = Json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    Json row = Json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(m(i, j) == 0 ? 0.0 : m(i, j));  // no -0
    rows.push_back(row);
  }
  return rows;
}

// Shortest text that reads back as the same double.
std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The values of a `mbgen fit --json` result (schema mbgen-fit/1) put into `p`: the file `path`, or `text` when given
// (named `path` in messages); DataError for another file or a parameter the model does not have.
void take_fit_result(const std::string& path, const std::optional<std::string>& text, const ModelInfo& info,
                     Eigen::VectorXd& p) {
  std::ifstream file;
  std::istringstream given(text ? *text : std::string());
  if (!text) {
    file.open(path, std::ios::binary);
    if (!file) throw DataError(path, 0, 0, "cannot read the file");
  }
  std::istream& in = text ? static_cast<std::istream&>(given) : file;
  Json j;
  try {
    j = Json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw DataError(path, 0, 0, std::string("not JSON: ") + e.what());
  }
  if (!j.is_object() || j.value("schema", "") != "mbgen-fit/1" || !j.contains("parameters") ||
      !j["parameters"].is_object())
    throw DataError(path, 0, 0, "not a fit result: expected the JSON of `mbgen fit --json` (schema mbgen-fit/1)");
  for (const auto& [name, entry] : j["parameters"].items()) {
    const int i = info.parameter_index(name);
    if (i < 0) throw DataError(path, 0, 0, "parameter `" + name + "` of the fit result is not in the model");
    if (!entry.is_object() || !entry.contains("value") || !entry["value"].is_number())
      throw DataError(path, 0, 0, "parameter `" + name + "` has no numeric value");
    p[i] = entry["value"].get<double>();
  }
}

// `LO:HI:N`: N >= 2 lines from LO to HI Hz, evenly spaced, both ends included.
std::vector<double> frequency_grid(const std::string& text) {
  const std::size_t a = text.find(':'), b = text.find(':', a == std::string::npos ? 0 : a + 1);
  const auto fail = [&] {
    throw CLI::ValidationError("--frf", "expected LO:HI:N (Hz, 0 <= LO < HI, N lines >= 2), got `" + text + "`");
  };
  if (a == std::string::npos || b == std::string::npos) fail();
  double lo = 0, hi = 0;
  long n = 0;
  try {
    std::size_t used = 0;
    lo = std::stod(text.substr(0, a), &used);
    if (used != a) fail();
    hi = std::stod(text.substr(a + 1, b - a - 1), &used);
    if (used != b - a - 1) fail();
    n = std::stol(text.substr(b + 1), &used);
    if (used != text.size() - b - 1) fail();
  } catch (const std::logic_error&) {
    fail();
  }
  if (!(lo >= 0) || !(hi > lo) || !std::isfinite(hi) || n < 2 || n > 10000000) fail();
  std::vector<double> f;
  for (long k = 0; k < n; ++k) f.push_back(k + 1 == n ? hi : lo + (hi - lo) * static_cast<double>(k) / (n - 1));
  return f;
}

// The FRFs in the readers' CSV layout (write_frf_csv).
std::string frf_csv(const ModelInfo& info, const FrfResult& r) {
  FrfData data;
  data.f_hz = Eigen::Map<const Eigen::VectorXd>(r.freqs_hz.data(), static_cast<Eigen::Index>(r.freqs_hz.size()));
  for (std::size_t o = 0; o < info.outputs.size(); ++o)
    for (std::size_t i = 0; i < info.inputs.size(); ++i) {
      FrfChannel c{info.outputs[o], info.inputs[i], Eigen::VectorXcd(data.f_hz.size()), std::nullopt};
      for (std::size_t k = 0; k < r.H.size(); ++k)
        c.values[static_cast<Eigen::Index>(k)] = r.H[k](static_cast<Eigen::Index>(o), static_cast<Eigen::Index>(i));
      data.channels.push_back(std::move(c));
    }
  std::ostringstream out;
  write_frf_csv(out, data);
  return out.str();
}

Json frf_json(const ModelInfo& info, const FrfResult& r) {
  Json channels = Json::object();
  for (std::size_t o = 0; o < info.outputs.size(); ++o)
    for (std::size_t i = 0; i < info.inputs.size(); ++i) {
      Json re = Json::array(), im = Json::array();
      for (const Eigen::MatrixXcd& h : r.H) {
        re.push_back(h(static_cast<Eigen::Index>(o), static_cast<Eigen::Index>(i)).real());
        im.push_back(h(static_cast<Eigen::Index>(o), static_cast<Eigen::Index>(i)).imag());
      }
      channels[info.outputs[o] + "/" + info.inputs[i]] = {{"re", re}, {"im", im}};
    }
  return {{"f_hz", r.freqs_hz}, {"channels", channels}};
}

// The FRFs as UFF 58 (one dataset per channel: response node o + 1, reference node 1001 + i, both +X) and the
// mapping file that names the points (`OUT.uff.map`, which the readers take beside the file).
struct UffFiles {
  std::string data, mapping;
};
UffFiles frf_uff(const ir::ModelIr& model, const std::string& model_path, const ModelInfo& info, const FrfResult& r) {
  UffFiles out;
  out.mapping = "# mbgen export " + model_path + ": UFF points to model channels\n";
  for (std::size_t o = 0; o < info.outputs.size(); ++o)
    out.mapping += uff_point_key(static_cast<int>(o) + 1, 1) + " = " + info.outputs[o] + "\n";
  for (std::size_t i = 0; i < info.inputs.size(); ++i)
    out.mapping += uff_point_key(1001 + static_cast<int>(i), 1) + " = " + info.inputs[i] + "\n";
  const std::size_t n = r.freqs_hz.size();
  const double increment = n > 1 ? (r.freqs_hz.back() - r.freqs_hz.front()) / static_cast<double>(n - 1) : 1.0;
  const bool even = uff58_even_increment_exact(increment) && uff58_even_increment_exact(r.freqs_hz.front() + increment);
  std::ostringstream text;
  for (std::size_t o = 0; o < info.outputs.size(); ++o) {
    ir::OutputKind kind = ir::OutputKind::Displacement;
    for (const ir::Output& declared : model.outputs)
      if (declared.name == info.outputs[o]) kind = declared.kind;
    for (std::size_t i = 0; i < info.inputs.size(); ++i) {
      Uff58Record rec;
      rec.id = {"mbgen export " + model_path, info.outputs[o] + "/" + info.inputs[i], "NONE", "NONE", "NONE"};
      rec.function_type = 4;
      rec.response_entity = rec.reference_entity = "mbgen";
      rec.response_node = static_cast<int>(o) + 1, rec.response_direction = 1;
      rec.reference_node = 1001 + static_cast<int>(i), rec.reference_direction = 1;
      rec.ordinate_data_type = 6;
      rec.even_spacing = even;
      rec.abscissa_min = r.freqs_hz.front(), rec.abscissa_increment = increment;
      rec.abscissa_type = 18, rec.abscissa_label = "Frequency", rec.abscissa_units = "Hz";
      rec.ordinate_type = kind == ir::OutputKind::Acceleration ? 12 : kind == ir::OutputKind::Velocity ? 11 : 8;
      rec.ordinate_label = ir::to_string(kind);
      rec.ordinate_units = kind == ir::OutputKind::Acceleration ? "m/s^2" : kind == ir::OutputKind::Velocity ? "m/s" : "m";
      rec.ordinate_denominator_type = 13, rec.ordinate_denominator_label = "force", rec.ordinate_denominator_units = "N";
      rec.x.resize(static_cast<Eigen::Index>(n));
      rec.y.resize(static_cast<Eigen::Index>(n));
      for (std::size_t k = 0; k < n; ++k) {
        rec.x[static_cast<Eigen::Index>(k)] = r.freqs_hz[k];
        rec.y[static_cast<Eigen::Index>(k)] = r.H[k](static_cast<Eigen::Index>(o), static_cast<Eigen::Index>(i));
      }
      write_uff58(text, rec);
    }
  }
  out.data = text.str();
  return out;
}

// The model's modes at its sensor points as UFF 55, the points' coordinates as UFF 15 and the lines between them
// as UFF 82 (sensor_geometry) before them, and the mapping file that names the points. A shape at an output is the motion of its point along its axis: the output map's row
// (displacement, velocity or acceleration map; one of them holds the output) applied to the mode's coordinates.
UffFiles modes_uff(const ir::ModelIr& model, const std::string& model_path, const ModelInfo& info,
                   const Eigen::VectorXd& p, const std::map<std::string, std::string>& sets, const ModelMatrices& m) {
  std::map<std::string, double> values;
  for (const auto& [name, text] : sets) values[name] = std::stod(text);
  for (std::size_t i = 0; i < info.parameters.size(); ++i)
    values[info.parameters[i].name] = p[static_cast<Eigen::Index>(i)];
  if (info.outputs.empty())
    throw DataError(model_path, 0, 0, "UFF modes are written at the model's outputs (its sensor points), and it has none");
  const SensorGeometry geometry = sensor_geometry(model, values);
  const std::vector<Mode> modes = modal_analysis(m.M, m.C, m.K);
  if (modes.empty()) throw DataError(model_path, 0, 0, "the model has no oscillating mode to write as UFF 55");
  std::vector<UffPoint> points;
  for (const std::string& name : info.outputs) points.push_back(geometry.outputs.at(name));
  const Eigen::MatrixXd maps = m.Cd + m.Cv + m.Ca;
  Eigen::MatrixXcd shapes(static_cast<Eigen::Index>(points.size()), static_cast<Eigen::Index>(modes.size()));
  std::vector<std::complex<double>> eigenvalues;
  for (std::size_t k = 0; k < modes.size(); ++k) {
    eigenvalues.push_back(modes[k].eigenvalue);
    shapes.col(static_cast<Eigen::Index>(k)) = maps.cast<std::complex<double>>() * modes[k].shape;
  }
  UffFiles out;
  out.data = uff55_modes_text(points, eigenvalues, shapes, 8, "mbgen export " + model_path, "model modes",
                              geometry.nodes, geometry.traces);
  out.mapping = uff_points_mapping("mbgen export " + model_path, info.outputs, points);
  return out;
}

std::string modes_csv(const ModelInfo& info, const std::vector<Mode>& modes) {
  std::ostringstream out;
  out << "mode,f_hz,zeta";
  for (const std::string& c : info.coordinates) out << "," << c << ".re," << c << ".im";
  out << "\n";
  for (std::size_t m = 0; m < modes.size(); ++m) {
    out << m + 1 << "," << number(modes[m].f_hz) << "," << number(modes[m].zeta);
    for (Eigen::Index c = 0; c < modes[m].shape.size(); ++c)
      out << "," << number(modes[m].shape[c].real()) << "," << number(modes[m].shape[c].imag());
    out << "\n";
  }
  return out.str();
}

Json modes_json(const std::vector<Mode>& modes) {
  Json out = Json::array();
  for (const Mode& m : modes) {
    Json re = Json::array(), im = Json::array();
    for (Eigen::Index c = 0; c < m.shape.size(); ++c) re.push_back(m.shape[c].real()), im.push_back(m.shape[c].imag());
    out.push_back({{"f_hz", m.f_hz},
                   {"zeta", m.zeta},
                   {"eigenvalue", {{"re", m.eigenvalue.real()}, {"im", m.eigenvalue.imag()}}},
                   {"shape", {{"re", re}, {"im", im}}}});
  }
  return out;
}

}  // namespace

void check_export_request(const ExportRequest& r) {
  const std::string &what = r.what, &format = r.format, &output = r.output;
  if (what == "frf" && r.grid.empty()) throw CLI::ValidationError("--frf", "--what frf needs the grid: --frf LO:HI:N");
  if (what != "frf" && !r.grid.empty()) throw CLI::ValidationError("--frf", "only with --what frf");
  if (format == "csv" && (what == "matrices" || what == "state-space"))
    throw CLI::ValidationError("--format", "csv holds one table: frf or modes; matrices and the state space are json");
  if (format == "uff" && what != "frf" && what != "modes")
    throw CLI::ValidationError("--format", "uff holds FRFs (--what frf, UFF 58) or modes (--what modes, UFF 55)");
  if (format == "uff" && output == "-")
    throw CLI::ValidationError("-o", "a UFF file comes with its mapping file (OUT.map): name a file");
  if (format == "mat" && !mat_file_available())
    throw CLI::ValidationError("--format", "mat needs libmatio, and this mbgen was built without it (install "
                                           "libmatio-dev, scripts/setup does, and build again)");
  if (format == "mat" && output == "-") throw CLI::ValidationError("-o", "a .mat file is binary: name a file");
  if (what == "frf") frequency_grid(r.grid);
}

ExportText export_model(const ExportRequest& request) {
  check_export_request(request);
  const std::string &model_path = request.model_path, &what = request.what, &format = request.format;
  const std::vector<double> f = what == "frf" ? frequency_grid(request.grid) : std::vector<double>{};
  symbolic::DeriveOptions derive;
  derive.set = request.set;
  const ir::ModelIr model = frontend::parse_file(model_path);
  const auto evaluator = evaluator::make_evaluator(model, derive);
  const ModelInfo& info = evaluator->info();
  Eigen::VectorXd p = info.default_values();
  if (!request.fit_result.empty()) take_fit_result(request.fit_result, request.fit_result_text, info, p);
  ModelMatrices m;
  evaluator->evaluate(p, m);

  if (format == "mat") {
    const FrfResult frfs = what == "frf" ? frf(*evaluator, p, f) : FrfResult{};
    return {export_mat(model_path, what, info, p, m, what == "frf" ? &frfs : nullptr), ""};
  }
  if (format == "uff") {
    const UffFiles files = what == "modes" ? modes_uff(model, model_path, info, p, derive.set, m)
                                           : frf_uff(model, model_path, info, frf(*evaluator, p, f));
    return {files.data, files.mapping};
  }
  if (format == "csv")
    return {what == "frf" ? frf_csv(info, frf(*evaluator, p, f)) : modes_csv(info, modal_analysis(m.M, m.C, m.K)), ""};
  Json j;
  j["schema"] = "mbgen-export/1";
  j["model"] = model_path;
  j["what"] = what;
  Json values = Json::object();
  for (std::size_t i = 0; i < info.parameters.size(); ++i)
    values[info.parameters[i].name] = p[static_cast<Eigen::Index>(i)];
  j["parameters"] = values;
  j["coordinates"] = info.coordinates;
  j["inputs"] = info.inputs;
  j["outputs"] = info.outputs;
  if (what == "matrices") {
    j["M"] = matrix_json(m.M), j["C"] = matrix_json(m.C), j["K"] = matrix_json(m.K), j["B"] = matrix_json(m.B);
    j["Cd"] = matrix_json(m.Cd), j["Cv"] = matrix_json(m.Cv), j["Ca"] = matrix_json(m.Ca);
  } else if (what == "state-space") {
    const StateSpace ss = state_space(m);
    j["A"] = matrix_json(ss.A), j["B"] = matrix_json(ss.B), j["C"] = matrix_json(ss.C), j["D"] = matrix_json(ss.D);
  } else if (what == "modes") {
    j["modes"] = modes_json(modal_analysis(m.M, m.C, m.K));
  } else {
    j["frf"] = frf_json(info, frf(*evaluator, p, f));
  }
  return {j.dump(2) + "\n", ""};
}

int run_export(int argc, char** argv) {
  CLI::App app{"Write a model's numbers for another tool: M, C, K, B and the output maps, the state space, the modes "
               "or FRFs on a frequency grid, at the model's values or at a fit's estimate.",
               "mbgen export"};
  std::string model_path, what = "matrices", format = "json", output = "-", grid, fit_result;
  std::vector<std::string> sets;
  app.add_option("model", model_path, "model file (.mdl); - reads standard input")->required();
  app.add_option("--what", what, "matrices (default), state-space, modes or frf")
      ->check(CLI::IsMember({"matrices", "state-space", "modes", "frf"}));
  app.add_option("--frf", grid, "with --what frf: the frequency grid LO:HI:N (Hz; N lines, both ends included)");
  app.add_option("--format", format, "json (default, schema mbgen-export/1), csv (frf: the FRF CSV layout mbgen "
                                     "reads; modes: one row per mode) or uff (frf: UFF 58; modes: UFF 55 at the sensor "
                                     "points with their UFF 15 nodes and UFF 82 trace lines; the .map beside it names "
                                     "the points) or mat (MATLAB "
                                     "variables, the JSON's content)")
      ->check(CLI::IsMember({"json", "csv", "uff", "mat"}));
  app.add_option("--fit-result", fit_result, "the parameters' values from a `mbgen fit --json` result");
  app.add_option("--set", sets, "override a parameter's value: NAME=VALUE (repeatable)");
  app.add_option("-o,--output", output, "file to write (default: standard output)");
  app.set_version_flag("--version", version_text());
  return run_guarded(app, argc, argv, [&] {
    ExportRequest request;
    request.model_path = model_path;
    request.what = what;
    request.format = format;
    request.grid = grid;
    request.fit_result = fit_result;
    request.output = output;
    check_export_request(request);
    request.set = parse_set_options(sets);
    OutputPlan plan;
    plan.files = {{"-o", output}, {"-o (its UFF mapping file)", format == "uff" ? output + ".map" : ""}};
    plan.inputs = {model_path};
    if (!fit_result.empty()) plan.inputs.push_back(fit_result);
    plan.check();
    const ExportText text = export_model(request);
    OutputFiles out;
    out.add(output, text.data);
    if (format == "uff") out.add(output + ".map", text.mapping);
    out.commit();
    return 0;
  }, &model_path);
}

}  // namespace mbgen::cli
