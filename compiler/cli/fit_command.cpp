// `mbgen fit MODEL.mdl --data FILE [--data FILE ...] [--method NAME] [--json OUT.json] [--report DIR]`:
// estimates the model's `estimate` parameters from measured FRFs or time records
// (runtime/include/mbgen/estimation/fit.hpp).
#include <mbgen/estimation/fit_report.hpp>
#include <mbgen/methods/method_table.hpp>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <nlohmann/json.hpp>

#include "cli/command_runs.hpp"
#include "cli/commands.hpp"
#include "cli/data_checks.hpp"
#include "cli/load_data.hpp"
#include "cli/method_option.hpp"
#include "cli/modal_start_option.hpp"
#include "cli/output_files.hpp"
#include "cli/parameter_roles.hpp"
#include "cli/number_checks.hpp"
#include "cli/run_guarded.hpp"
#include "cli/seed_option.hpp"
#include "cli/starts_option.hpp"
#include "cli/version.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"

namespace mbgen::cli {

namespace {

std::string summary(const FitResult& r) {
  std::string out;
  for (const std::string& w : r.warnings) out += "warning: " + w + "\n";
  // A fit whose estimates mostly ended at bounds has not found the model in the data: said first, in one line.
  const auto at_bound = std::count_if(r.parameters.begin(), r.parameters.end(),
                                      [](const ParameterEstimate& p) { return !p.at_bound.empty(); });
  if (at_bound >= 2 && 2 * at_bound > static_cast<long>(r.parameters.size()))
    out += "warning: " + std::to_string(at_bound) + " of the " + std::to_string(r.parameters.size()) +
           " estimated parameters ended at a bound: the model does not fit these data as it is (a start far from the "
           "truth: try --start-from-modes; a sign or unit of the data; or a structure the model lacks)\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-12s %14s %14s %12s  %s\n", "parameter", "prior", "estimate", "std", "");
  out += line;
  for (const ParameterEstimate& p : r.parameters) {
    const std::string note = !p.at_bound.empty() ? "at its " + p.at_bound + " bound: the data pull it beyond; no std"
                             : !p.identifiable ? "not identifiable: kept at the prior"
                                               : "";
    const bool has_std = std::find(r.estimated.begin(), r.estimated.end(), p.name) != r.estimated.end();
    char std_text[32] = "-";  // the method gives no std for it (docs/methods.md)
    if (has_std) std::snprintf(std_text, sizeof std_text, "%.3g", p.std);
    std::snprintf(line, sizeof line, "%-12s %14.6g %14.6g %12s  %s\n", p.name.c_str(), p.prior, p.value, std_text,
                  note.c_str());
    out += line;
  }
  // An empty table alone said nothing of why.
  if (r.parameters.empty())
    out += "(no parameter is declared `estimate`: the model is compared with the data at its values)\n";
  std::snprintf(line, sizeof line, "\nnrmse %.4g   BIC %.6g   (%ld residuals, %s)\n", r.nrmse, r.bic, r.residual_count,
                r.method.c_str());
  out += line;
  if (!r.converged) out += "warning: the fit did not converge (" + r.stop_reason + ")\n";
  out += "modes at the estimate:";
  for (const Mode& m : r.modes) {
    std::snprintf(line, sizeof line, " %.1f Hz (%.3g)", m.f_hz, m.zeta);
    out += line;
  }
  out += "\n";
  // The residual tests' verdicts and the scores on other data (docs/estimation.md), one line per record and file.
  std::string tested_file;
  for (const ChannelResidualTest& t : r.residual_tests) {
    if (t.data_set != tested_file) out += (tested_file.empty() ? "" : "\n") + ("residual tests, " + t.data_set + ":");
    tested_file = t.data_set;
    out += " " + t.output + " " + (t.whiteness.passed() ? "white" : "NOT WHITE");
    for (const auto& [input, x] : t.inputs)
      out += (x.passed() ? ", independent of " : ", CORRELATED WITH ") + input;
    out += ";";
  }
  if (!tested_file.empty()) out += "\n";
  for (const ValidationScore& v : r.validation) {
    out += "validation, " + v.file + ": fit";
    for (const ChannelValidation& c : v.channels) {
      std::snprintf(line, sizeof line, " %s %.1f %%", c.channel.c_str(), c.fit_percent);
      out += line;
    }
    out += "\n";
  }
  // A method's own account of what it did (method_details.NAME.summary), e.g. two-step's route.
  for (const auto& [name, text] : r.method_details) {
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_object() && j.contains("summary") && j["summary"].is_string())
      out += name + ": " + j["summary"].get<std::string>() + "\n";
  }
  return out;
}

}  // namespace

FitRun fit_model(FitRequest request) {
  const MethodDescriptor* const method = &method_named(request.method, "fit");
  symbolic::DeriveOptions derive;
  derive.set = std::move(request.set);
  const ir::ModelIr model = read_model_with_roles(request.model_path, request.roles, derive.set).model;
  FitRun run;
  run.model = evaluator::make_evaluator(model, derive);
  const Model& evaluator = *run.model;
  std::vector<DataSet>& data = run.data;
  data = load_data(request.data_paths, evaluator.info(), model, derive.set);
  if (!request.band.empty()) data = within_band(data, parse_band("--band", request.band));
  // A named method that cannot use the data is bad input (status 1), as docs/interfaces.md says.
  check_method_takes(*method, data);
  if (request.start_from_modes && !method->output_error)
    throw FitError("fit: error: --start-from-modes starts the output-error search; --method " + method->name +
                   " has its own starts (drop --start-from-modes or use --method auto)");
  // Validation data are read and checked before the fit, so that a bad file stops the command at once. They are not
  // cut to --band: they are scored as they are.
  if (!request.validate_paths.empty()) {
    run.validation = load_data(request.validate_paths, evaluator.info(), model, derive.set);
    check_validation_data(evaluator, run.validation);
  }
  std::optional<ModalStart> modal_start;
  if (request.start_from_modes) modal_start = add_start_from_modes(evaluator, data, request.options, "fit");
  const FitOptions& options = request.options;
  FitResult& result = run.result;
  MethodOptions& method_options = request.method_options;
  method_options.analytical_solver = analytical_solver(model, derive);
  result = run_method(*method, {evaluator, data, options, method_options});
  if (modal_start) result.method_details["start_from_modes"] = start_from_modes_details(*modal_start);
  result.model = request.model_path;
  result.seed = options.seed;
  result.warnings = passivity_warnings(model, data);
  // The residual tests and the validation simulate the model at the estimate; where that fails (an estimate of a
  // method without a stability constraint may be unstable) the fit's result stands and a warning says what is missing.
  result.residual_test_lags = request.residual_lags;
  try {
    result.residual_tests = residual_tests(evaluator, data, result.values, request.residual_lags);
  } catch (const std::exception& e) {
    result.warnings.push_back(std::string("no residual tests: ") + e.what());
  }
  for (const DataSet& d : run.validation) {
    try {
      result.validation.push_back(validation_scores(evaluator, {d}, result.values).front());
    } catch (const std::exception& e) {
      result.warnings.push_back("no validation on " + d.file() + ": " + e.what());
      result.validation.push_back(ValidationScore{d.file(), d.is_frf(), {}});
    }
  }
  return run;
}

int run_fit(int argc, char** argv) {
  CLI::App app{"Estimate the parameters marked `estimate` from measured FRFs or time records: output error with "
               "analytic Jacobians, bounds by reparameterisation, a deterministic multi-start global search, "
               "uncertainties and an identifiability report.",
               "mbgen fit"};
  std::string model_path, method = "auto", json_path, report_dir, band;
  std::vector<std::string> data_paths, sets;
  FitOptions options;
  app.add_option("model", model_path, "model file (.mdl); - reads standard input")->required();
  app.add_option("--data", data_paths, "measured data: CSV (time or FRF) or UFF 58; repeatable, fitted jointly")->required();
  add_method_choice(app, method);
  app.add_option("--json", json_path, "write the result (schema mbgen-fit/1); - for standard output");
  std::vector<std::string> validate_paths;
  app.add_option("--validate", validate_paths, "score the estimate on other data (same kinds as --data; repeatable): "
                 "the fit percentage per channel, as MATLAB's compare (docs/estimation.md)");
  int residual_lags = 25;
  app.add_option("--residual-lags", residual_lags, "time records: the residual tests' largest lag L (default 25, as "
                 "MATLAB's resid; at most a quarter of a record's samples are used; docs/estimation.md)")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--report", report_dir, "write a report directory (Markdown with Bode overlays and residual plots)");
  app.add_option("--set", sets, "override a parameter's value: NAME=VALUE (repeatable)");
  RoleOptions roles;
  add_role_options(app, roles);
  app.add_option("--starts", options.starts, "number of starts of the global search (default 16)")
      ->check(starts_range());
  app.add_option("--seed", options.seed, "seed of the global search (default 1)")->check(seed_check());
  bool from_modes = false;
  app.add_flag("--start-from-modes", from_modes, "output error: also start the search where the model's modes "
               "match the data's own (LSCF modes paired by MAC; docs/estimation.md)");
  app.add_option("--band", band, "fit only the FRF lines within LO:HI Hz (the band the model is meant to represent)");
  MethodOptions method_options;
  add_method_own_options(app, method_options);
  app.set_version_flag("--version", version_text());
  return run_guarded(app, argc, argv, [&] {
    FitRequest request;
    request.set = parse_set_options(sets);
    OutputPlan plan;
    plan.files = {{"--json", json_path}};
    plan.report_dir = report_dir;
    plan.inputs = data_paths;
    plan.inputs.insert(plan.inputs.end(), validate_paths.begin(), validate_paths.end());
    plan.inputs.push_back(model_path);
    plan.check();
    request.model_path = model_path;
    request.data_paths = data_paths;
    request.validate_paths = validate_paths;
    request.residual_lags = residual_lags;
    request.method = method;
    request.roles = roles;
    request.options = options;
    request.start_from_modes = from_modes;
    request.options.progress = [](const FitProgress& p) {
      progress_line("fit: " + p.stage + " start " + std::to_string(p.start + 1) + "/" + std::to_string(p.starts) +
                    ", iteration " + std::to_string(p.iteration) + ", cost " + std::to_string(p.cost));
    };
    request.band = band;
    request.method_options = method_options;
    const FitRun run = fit_model(std::move(request));
    progress_done();
    const FitResult& result = run.result;
    const auto& evaluator = run.model;
    const std::vector<DataSet>& data = run.data;

    OutputFiles out;
    if (!json_path.empty()) out.add(json_path, fit_result_json(result));
    if (!report_dir.empty()) write_fit_report(out.stage_directory(report_dir), *evaluator, data, result, run.validation);
    out.commit();
    if (json_path != "-") std::cout << summary(result);
    return 0;
  }, &model_path);
}

}  // namespace mbgen::cli
