// mbgen.fit, mbgen.diagnose, mbgen.modal, mbgen.sensitivity, mbgen.monitor and mbgen.monitor_output_only: the
// commands' own functions (cli/command_runs.hpp) with their options given as keyword arguments, returning the content
// of the JSON the command writes with --json (docs/interfaces.md: mbgen-fit/1, mbgen-diagnosis/1, mbgen-modal/1,
// mbgen-sensitivity/1, mbgen-monitor/1, mbgen-monitor-operational/1), made by the same code and read back by Python's
// json module.
#include <pybind11/stl.h>

#include <mbgen/dynamics/dynamics_error.hpp>
#include <mbgen/estimation/fit_report.hpp>
#include <mbgen/monitoring/monitor_report.hpp>

#include <cmath>

#include "bindings.hpp"
#include "cli/command_runs.hpp"
#include "cli/commands.hpp"
#include "cli/load_data.hpp"
#include "cli/number_checks.hpp"
#include "cli/seed_option.hpp"
#include "cli/starts_option.hpp"
#include "diagnosis/engine/diagnosis_json.hpp"
#include "frontend/diagnostics.hpp"

namespace mbgen::python {

namespace {

// An option's value checked by the validator the command line applies to it (its message is the command's).
void check(const std::string& option, CLI::Validator validator, std::string text) {
  if (const std::string problem = validator(text); !problem.empty()) usage_error(option, problem);
}

void member(const std::string& option, const std::string& value, const std::vector<std::string>& allowed) {
  for (const std::string& a : allowed)
    if (value == a) return;
  std::string list;
  for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
  usage_error(option, "`" + value + "` is none of " + list);
}

// A band as "LO:HI" (either side may be empty) or (LO, HI) with None for an open side, as --band's text.
std::string band_text(const py::object& band) {
  if (py::isinstance<py::str>(band)) return band.cast<std::string>();
  const py::sequence s = py::reinterpret_borrow<py::sequence>(band);
  if (!py::isinstance<py::sequence>(band) || py::len(s) != 2) usage_error("--band", "a band is \"LO:HI\" or (LO, HI)");
  return (s[0].is_none() ? "" : option_text(s[0])) + ":" + (s[1].is_none() ? "" : option_text(s[1]));
}

// The model file and its options: a path with the options given here, or a mbgen.Model with those it was loaded
// with and those given here after them (the command then refuses a parameter set twice, as it does).
std::string model_file(const py::object& model, ModelOptions& options) {
  if (!is_model(model)) return path_text(model);
  ModelOptions merged = model_options_of(model);
  merged.sets.insert(merged.sets.end(), options.sets.begin(), options.sets.end());
  const auto append = [](std::vector<std::string>& to, const std::vector<std::string>& from) {
    to.insert(to.end(), from.begin(), from.end());
  };
  append(merged.roles.fix, options.roles.fix);
  append(merged.roles.free, options.roles.free);
  append(merged.roles.bound, options.roles.bound);
  options = std::move(merged);
  return model_path(model);
}

// The model's file named in the message when its numeric dynamics fail, as the command does (run_guarded.hpp).
template <typename F>
auto guarded(const std::string& model, F f) {
  try {
    return released(f);  // a fit takes long
  } catch (const DynamicsError& e) {
    if (model.empty()) throw;
    throw frontend::ModelError(model, {}, e.what());
  }
}

void search_options(FitOptions& fit, const py::object& starts, const py::object& seed) {
  if (!starts.is_none()) {
    check("--starts", cli::starts_range(), py::str(starts));
    fit.starts = starts.cast<int>();
  }
  if (!seed.is_none()) {
    check("--seed", cli::seed_check(), py::str(seed));
    fit.seed = std::stoull(py::str(seed).cast<std::string>());
  }
}

py::object fit_command(const py::object& model, const py::object& data, const std::string& method,
                       const py::object& set, const py::object& fix, const py::object& free, const py::object& bound,
                       const py::object& starts, const py::object& seed, bool start_from_modes,
                       const py::object& band, const std::string& two_step_route, const py::object& two_step_model,
                       const py::object& two_step_criterion, const py::object& two_step_weighting,
                       const py::object& ekf_drift, const py::object& validate, const py::object& residual_lags) {
  member("--method", method, method_names());
  member("--two-step-route", two_step_route, find_method_option("--two-step-route")->choices);
  ModelOptions options = model_options(set, fix, free, bound);
  cli::FitRequest request;
  request.model_path = model_file(model, options);
  request.set = cli::parse_set_options(options.sets);
  request.roles = options.roles;
  request.data_paths = paths(data, "--data");
  request.method = method;
  search_options(request.options, starts, seed);
  request.start_from_modes = start_from_modes;
  if (!band.is_none()) request.band = band_text(band);
  // The methods' options, checked against the choices the method table declares (as the command does).
  MethodOptions& methods = request.method_options;
  const auto choose = [&methods](const char* flag, const std::string& value) {
    const MethodOption& o = *find_method_option(flag);
    member(flag, value, o.choices);
    o.text(methods) = value;
  };
  choose("--two-step-route", two_step_route);
  if (!two_step_model.is_none()) choose("--two-step-model", two_step_model.cast<std::string>());
  if (!two_step_criterion.is_none()) choose("--two-step-criterion", two_step_criterion.cast<std::string>());
  if (!two_step_weighting.is_none()) choose("--two-step-weighting", two_step_weighting.cast<std::string>());
  if (!ekf_drift.is_none()) {
    check("--ekf-drift", cli::non_negative_number(), option_text(ekf_drift));
    find_method_option("--ekf-drift")->number(methods) = ekf_drift.cast<double>();
  }
  if (!validate.is_none()) request.validate_paths = paths(validate, "--validate");
  if (!residual_lags.is_none()) {
    check("--residual-lags", CLI::Range(1, 1000000), option_text(residual_lags));
    request.residual_lags = residual_lags.cast<int>();
  }
  const std::string path = request.model_path;
  const std::string json = guarded(path, [&] { return fit_result_json(cli::fit_model(std::move(request)).result); });
  return json_to_python(json);
}

py::object diagnose_command(const py::object& model, const py::object& data, const py::object& set,
                            const py::object& fix, const py::object& free, const py::object& bound,
                            const py::object& starts, const py::object& seed, bool start_from_modes,
                            const py::object& full_fits,
                            const py::object& fit_band, const std::string& method) {
  member("--method", method, method_names());
  ModelOptions options = model_options(set, fix, free, bound);
  cli::DiagnoseRequest request;
  request.model_path = model_file(model, options);
  request.options.set = cli::parse_set_options(options.sets);
  request.roles = options.roles;
  request.data_paths = paths(data, "--data");
  search_options(request.options.fit, starts, seed);
  request.options.start_from_modes = start_from_modes;
  if (!full_fits.is_none()) {
    check("--full-fits", cli::non_negative_number(), py::str(full_fits));
    request.options.full_fits = full_fits.cast<int>();
  }
  if (!fit_band.is_none()) request.fit_band = band_text(fit_band);
  request.method = method;
  const std::string path = request.model_path;
  // As the command without --extended: no extended model is written, and the JSON's `extended_model` is empty.
  const std::string json =
      guarded(path, [&] { return cli::diagnose_run_json(cli::diagnose_model(std::move(request)), ""); });
  return json_to_python(json);
}

py::object modal_command(const py::object& data, const py::object& band, const py::object& model,
                         const py::object& set, const py::object& max_order, const py::object& select, bool refine,
                         const std::string& quantity) {
  member("--quantity", quantity, {"auto", "receptance", "mobility", "accelerance"});
  cli::ModalRequest request;
  request.data_paths = paths(data, "--data");
  if (!band.is_none()) {
    const cli::Band b = cli::parse_band("--band", band_text(band));
    request.band = {b.lo, b.hi};
  }
  ModelOptions options = model_options(set, py::none(), py::none(), py::none());
  if (!model.is_none()) {
    request.model_path = model_file(model, options);
    // modal takes no roles: a value --fix gave is the value it compares at.
    for (const std::string& f : options.roles.fix)
      if (f.find('=') != std::string::npos) options.sets.push_back(f);
  } else if (!options.sets.empty()) {
    usage_error("--set", "needs --model");
  }
  request.sets = options.sets;
  if (!max_order.is_none()) {
    check("--max-order", cli::positive_number(), py::str(max_order));
    request.options.lscf.max_order = max_order.cast<int>();
  }
  if (!select.is_none())
    for (const py::handle& f : select) {
      check("--select", cli::positive_number(), option_text(f));
      request.options.select_hz.push_back(f.cast<double>());
    }
  request.options.refine = refine;
  request.quantity = quantity;
  const std::string path = request.model_path;
  const std::string json = guarded(path, [&] {
    const cli::ModalRun run = cli::modal_identification(std::move(request));
    return modal_result_json(run.input());
  });
  return json_to_python(json);
}


// A whole-number option checked by the command line's validator for it.
int int_option(const std::string& option, const py::handle& value, CLI::Validator validator) {
  if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
    usage_error(option, "expected a whole number, not " + py::repr(value).cast<std::string>());
  check(option, std::move(validator), py::str(value));
  return value.cast<int>();
}

// A number option checked by the command line's validator for it.
double number_option(const std::string& option, const py::handle& value, CLI::Validator validator) {
  const std::string text = option_text(value);
  check(option, std::move(validator), text);
  return std::stod(text);
}

// One text or a list of texts, as a repeatable option's values.
std::vector<std::string> texts(const py::object& value) {
  std::vector<std::string> out;
  if (py::isinstance<py::str>(value)) out.push_back(value.cast<std::string>());
  else
    for (const py::handle& v : value) out.push_back(py::str(v).cast<std::string>());
  return out;
}

py::object sensitivity_command(const py::object& model, bool global, const py::object& samples, const py::object& seed,
                               const py::object& spread, bool bounds, const py::object& sweep, const py::object& set,
                               const py::object& fix, const py::object& free, const py::object& bound) {
  if (!global && (bounds || !samples.is_none() || !seed.is_none() || !spread.is_none()))
    throw CLI::ValidationError("--samples, --seed, --spread and --bounds need --global");
  ModelOptions options = model_options(set, fix, free, bound);
  cli::SensitivityRequest request;
  request.model_path = model_file(model, options);
  request.set = cli::parse_set_options(options.sets);
  request.roles = options.roles;
  request.global = global;
  request.bounds = bounds;
  if (!samples.is_none()) request.sobol.samples = int_option("--samples", samples, CLI::Range(16, 1 << 22));
  if (!seed.is_none()) {
    check("--seed", cli::seed_check(), py::str(seed));
    request.sobol.seed = std::stoull(py::str(seed).cast<std::string>());
  }
  if (!spread.is_none()) request.spread = number_option("--spread", spread, CLI::Range(1e-9, 10.0));
  // Sweeps: "NAME=LO:HI:N", a list of them, or a dict NAME -> (LO, HI, N).
  if (py::isinstance<py::dict>(sweep)) {
    for (const auto& [name, range] : sweep.cast<py::dict>()) {
      const py::sequence lo_hi_n = py::reinterpret_borrow<py::sequence>(range);
      if (!py::isinstance<py::sequence>(range) || py::isinstance<py::str>(range) || py::len(lo_hi_n) != 3)
        usage_error("--sweep", py::str(name).cast<std::string>() + ": expected (LO, HI, N)");
      request.sweeps.push_back(py::str(name).cast<std::string>() + "=" + option_text(lo_hi_n[0]) + ":" +
                               option_text(lo_hi_n[1]) + ":" + py::str(lo_hi_n[2]).cast<std::string>());
    }
  } else if (!sweep.is_none()) {
    request.sweeps = texts(sweep);
  }
  const std::string path = request.model_path;
  const std::string json = guarded(path, [&] {
    const cli::SensitivityRun run = cli::sensitivity_analysis(std::move(request));
    return sensitivity_json(run.input());
  });
  return json_to_python(json);
}

py::object monitor_command(const py::object& model, const py::object& data, const py::object& baseline,
                           const py::object& run_length, const py::object& structural_ratio, const py::object& starts,
                           const py::object& warm_starts, const py::object& seed, bool diagnosis,
                           const py::object& set, const py::object& fix, const py::object& free,
                           const py::object& bound, const std::string& method) {
  member("--method", method, method_names());
  ModelOptions options = model_options(set, fix, free, bound);
  const std::string path = model_file(model, options);
  const std::vector<std::string> data_paths = paths(data, "--data");
  cli::MonitorSettings settings;
  settings.sets = options.sets;
  settings.roles = options.roles;
  settings.no_diagnosis = !diagnosis;
  settings.method = method;
  MonitorOptions& o = settings.options;
  if (!baseline.is_none()) o.baseline = int_option("--baseline", baseline, CLI::Range(2, 1000000));
  if (!run_length.is_none()) o.run_length = number_option("--run-length", run_length, CLI::Range(2.0, 1e12));
  if (!structural_ratio.is_none())
    o.structural_ratio = number_option("--structural-ratio", structural_ratio, CLI::Range(1.0001, 1e6));
  search_options(o.fit, starts, seed);
  if (!warm_starts.is_none()) o.warm_starts = int_option("--warm-starts", warm_starts, cli::starts_range());
  const std::string json = guarded(path, [&] {
    MonitorResult result = cli::monitor_machine(path, data_paths, std::move(settings));
    return monitor_result_json(result);
  });
  return json_to_python(json);
}

py::object monitor_output_only_command(const py::object& data, const py::object& baseline, const py::object& model,
                                       const py::object& false_alarm, const py::object& environmental_components,
                                       bool compensation, const py::object& references, const py::object& ignore,
                                       const py::object& max_order, const py::object& set, const py::object& fix,
                                       const py::object& free, const py::object& bound) {
  cli::OperationalRequest request;
  request.data_paths = paths(data, "--data");
  ModelOptions options = model_options(set, fix, free, bound);
  if (!model.is_none()) {
    request.model_path = model_file(model, options);
  } else {
    if (!options.sets.empty()) usage_error("--set", "needs --model");
    if (!options.roles.empty()) usage_error("--fix", "--fix, --free and --bound need --model");
  }
  request.sets = options.sets;
  request.roles = options.roles;
  if (!baseline.is_none()) request.options.baseline = int_option("--baseline", baseline, CLI::Range(2, 1000000));
  if (!false_alarm.is_none())
    request.options.false_alarm = number_option("--false-alarm", false_alarm, CLI::Range(1e-9, 0.5));
  if (!environmental_components.is_none())
    request.options.environmental_components =
        int_option("--environmental-components", environmental_components, CLI::Range(0, 1000));
  request.options.compensate = compensation;
  if (!references.is_none()) request.selection.references = texts(references);
  if (!ignore.is_none()) request.selection.ignore = texts(ignore);
  if (!max_order.is_none())
    request.identification.ssi.max_order = int_option("--max-order", max_order, CLI::Range(2, 400));
  const std::string path = request.model_path;
  const std::string json = guarded(path, [&] {
    const cli::OperationalRun run = cli::monitor_output_only(request);
    return operational_monitor_json(run.input());
  });
  return json_to_python(json);
}

}  // namespace

void register_commands(py::module_& m) {
  m.def("fit", &fit_command, py::arg("model"), py::arg("data"), py::arg("method") = "auto", py::kw_only(),
        py::arg("set") = py::none(), py::arg("fix") = py::none(), py::arg("free") = py::none(),
        py::arg("bound") = py::none(), py::arg("starts") = py::none(), py::arg("seed") = py::none(),
        py::arg("start_from_modes") = false, py::arg("band") = py::none(), py::arg("two_step_route") = "auto", py::arg("two_step_model") = py::none(),
        py::arg("two_step_criterion") = py::none(), py::arg("two_step_weighting") = py::none(),
        py::arg("ekf_drift") = py::none(), py::arg("validate") = py::none(), py::arg("residual_lags") = py::none(),
        "`mbgen fit`: estimates the model's `estimate` parameters from data files; returns the mbgen-fit/1 JSON "
        "as Python objects. model: a path or a mbgen.Model; data: a path or a list of paths; validate: data "
        "scored at the estimate (`--validate`), a path or a list of paths.");
  m.def("diagnose", &diagnose_command, py::arg("model"), py::arg("data"), py::kw_only(), py::arg("set") = py::none(),
        py::arg("fix") = py::none(), py::arg("free") = py::none(), py::arg("bound") = py::none(),
        py::arg("starts") = py::none(), py::arg("seed") = py::none(), py::arg("start_from_modes") = true,
        py::arg("full_fits") = py::none(),
        py::arg("fit_band") = py::none(), py::arg("method") = "auto",
        "`mbgen diagnose`: what the model gets wrong and which extension explains it; returns the "
        "mbgen-diagnosis/1 JSON as Python objects. method: `--method`, whose estimate (its options at their "
        "defaults) is one more start of the nominal fit.");
  m.def("modal", &modal_command, py::arg("data"), py::kw_only(), py::arg("band") = py::none(),
        py::arg("model") = py::none(), py::arg("set") = py::none(), py::arg("max_order") = py::none(),
        py::arg("select") = py::none(), py::arg("refine") = true, py::arg("quantity") = "auto",
        "`mbgen modal`: experimental modal analysis of measured FRFs; returns the mbgen-modal/1 JSON as Python "
        "objects.");
  m.def("sensitivity", &sensitivity_command, py::arg("model"), py::kw_only(), py::arg("global_") = false,
        py::arg("samples") = py::none(), py::arg("seed") = py::none(), py::arg("spread") = py::none(),
        py::arg("bounds") = false, py::arg("sweep") = py::none(), py::arg("set") = py::none(),
        py::arg("fix") = py::none(), py::arg("free") = py::none(), py::arg("bound") = py::none(),
        "`mbgen sensitivity`: how the model's modes depend on its parameters; returns the mbgen-sensitivity/1 JSON "
        "as Python objects. global_ is --global; sweep: \"NAME=LO:HI:N\", a list of them or a dict NAME -> "
        "(LO, HI, N).");
  m.def("monitor", &monitor_command, py::arg("model"), py::arg("data"), py::kw_only(), py::arg("baseline") = py::none(),
        py::arg("run_length") = py::none(), py::arg("structural_ratio") = py::none(), py::arg("starts") = py::none(),
        py::arg("warm_starts") = py::none(), py::arg("seed") = py::none(), py::arg("diagnosis") = true,
        py::arg("set") = py::none(), py::arg("fix") = py::none(), py::arg("free") = py::none(),
        py::arg("bound") = py::none(), py::arg("method") = "auto",
        "`mbgen monitor`: each data set (with a measured force) fitted in time order, parameter changes and "
        "structural changes detected; returns the mbgen-monitor/1 JSON as Python objects. diagnosis=False is "
        "--no-diagnosis; method: `--method`, whose estimate on each set (its options at their defaults) is one "
        "more start of that set's fit.");
  m.def("monitor_output_only", &monitor_output_only_command, py::arg("data"), py::kw_only(),
        py::arg("baseline") = py::none(), py::arg("model") = py::none(), py::arg("false_alarm") = py::none(),
        py::arg("environmental_components") = py::none(), py::arg("compensation") = true,
        py::arg("references") = py::none(), py::arg("ignore") = py::none(), py::arg("max_order") = py::none(),
        py::arg("set") = py::none(), py::arg("fix") = py::none(), py::arg("free") = py::none(),
        py::arg("bound") = py::none(),
        "`mbgen monitor --output-only`: monitoring in operation from response records; returns the "
        "mbgen-monitor-operational/1 JSON as Python objects. compensation=False is --no-compensation.");
}

}  // namespace mbgen::python
