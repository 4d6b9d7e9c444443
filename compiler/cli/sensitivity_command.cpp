// `mbgen sensitivity MODEL.mdl [--global] [--sweep NAME=LO:HI:N] [--json OUT] [--report DIR]`: how the model's modes
// depend on its parameters (runtime/include/mbgen/sensitivity/sensitivity.hpp, docs/sensitivity.md).
#include <mbgen/sensitivity/sensitivity_report.hpp>

#include <Eigen/Cholesky>

#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cli/command_runs.hpp"
#include "cli/commands.hpp"
#include "cli/parameter_roles.hpp"
#include "cli/load_data.hpp"
#include "cli/output_files.hpp"
#include "cli/run_guarded.hpp"
#include "cli/seed_option.hpp"
#include "cli/version.hpp"
#include "evaluator/shape_geometry.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"

namespace mbgen::cli {

namespace {

struct Sweep {
  std::string text;  // as given: NAME=LO:HI:N
  int index = 0;
  double lo = 0, hi = 0;
  int points = 0;
};

// NAME=LO:HI:N with a parameter of the model, finite LO < HI, N >= 2.
Sweep parse_sweep(const std::string& text, const ModelInfo& info) {
  const auto fail = [&](const std::string& why) { return CLI::ValidationError("--sweep", why + ": `" + text + "`"); };
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) throw fail("expected NAME=LO:HI:N");
  Sweep s;
  s.text = text;
  s.index = info.parameter_index(text.substr(0, eq));
  if (s.index < 0) throw fail("the model has no parameter `" + text.substr(0, eq) + "`");
  std::vector<std::string> parts;
  std::size_t start = eq + 1;
  for (std::size_t colon; (colon = text.find(':', start)) != std::string::npos; start = colon + 1)
    parts.push_back(text.substr(start, colon - start));
  parts.push_back(text.substr(start));
  if (parts.size() != 3) throw fail("expected NAME=LO:HI:N");
  try {
    std::size_t used = 0;
    s.lo = std::stod(parts[0], &used);
    if (used != parts[0].size()) throw fail("LO is not a number");
    s.hi = std::stod(parts[1], &used);
    if (used != parts[1].size()) throw fail("HI is not a number");
    s.points = std::stoi(parts[2], &used);
    if (used != parts[2].size()) throw fail("N is not an integer");
  } catch (const std::invalid_argument&) {  // what std::stod and std::stoi throw for text that is no number
    throw fail("expected numbers in LO:HI:N");
  } catch (const std::out_of_range&) {  // and for one beyond the type
    throw fail("expected numbers in LO:HI:N");
  }
  if (!std::isfinite(s.lo) || !std::isfinite(s.hi) || !(s.lo < s.hi)) throw fail("expected finite LO < HI");
  if (s.points < 2 || s.points > 100000) throw fail("expected 2 <= N <= 100000");
  return s;
}

// What a sweep means for the model, checked as --set's values are (status 1, at the parameter's declaration): the
// range within the declared bounds, and a positive definite mass matrix at every point. A sweep through negative
// masses or beyond the bounds was computed and reported with status 0 (while --set refuses both); one through a
// zero mass failed on a singular mass matrix without saying which value.
void check_sweep(const Sweep& s, const Model& model, const ir::ModelIr& declared) {
  const ParameterInfo& p = model.info().parameters[static_cast<std::size_t>(s.index)];
  ir::SourceLoc loc;
  for (const ir::Parameter& d : declared.parameters)
    if (d.name == p.name) loc = d.loc;
  if (s.lo < p.lower || s.hi > p.upper)
    throw frontend::ModelError(declared.file, loc, "--sweep {}: outside the bounds [{}, {}] declared for `{}`", s.text,
                               p.lower, p.upper, p.name);
  Eigen::VectorXd q = model.info().default_values();
  const Eigen::VectorXd values = Eigen::VectorXd::LinSpaced(s.points, s.lo, s.hi);
  ModelMatrices m;
  for (const double v : values) {
    q[s.index] = v;
    model.evaluate(q, m);
    if (Eigen::LLT<Eigen::MatrixXd>(m.M).info() != Eigen::Success)
      throw frontend::ModelError(declared.file, loc,
                                 "--sweep {}: at {} = {} the mass matrix is not positive definite (a mass or inertia "
                                 "is zero or negative)",
                                 s.text, p.name, v);
  }
}

}  // namespace

SensitivityRun sensitivity_analysis(SensitivityRequest request) {
  SensitivityRun run;
  run.model_path = request.model_path;
  run.sobol = request.sobol;
  run.global = request.global;
  symbolic::DeriveOptions derive;
  derive.set = request.set;
  run.declared = read_model_with_roles(request.model_path, request.roles, derive.set).model;
  run.model = evaluator::make_evaluator(run.declared, derive);
  const Model& model = *run.model;
  const ModelInfo& info = model.info();
  std::vector<Sweep> parsed;
  for (const std::string& s : request.sweeps) parsed.push_back(parse_sweep(s, info));
  for (const Sweep& s : parsed) check_sweep(s, model, run.declared);
  const Eigen::VectorXd p = info.default_values();

  run.local = local_sensitivity(model, p);
  run.visibility = mode_visibility(model, p);
  if (request.global) {
    std::vector<ParameterRange> ranges;
    try {
      ranges = parameter_ranges(info, p, request.spread, request.bounds);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError(request.bounds ? "--bounds" : "--spread", e.what());
    }
    std::ostringstream spread_text;
    spread_text << request.spread;
    run.range_text = request.bounds ? "their declared bounds"
                                    : "value * [1 - " + spread_text.str() + ", 1 + " + spread_text.str() +
                                          "] within their bounds";
    progress_line("sensitivity: Sobol indices, " + std::to_string(request.sobol.samples * (ranges.size() + 2)) +
                  " modal analyses on " + std::to_string(request.sobol.threads) + " threads");
    run.global_result = global_sensitivity(model, p, ranges, request.sobol);
    progress_done();
  }
  for (const Sweep& s : parsed) {
    progress_line("sensitivity: sweeping " + info.parameters[static_cast<std::size_t>(s.index)].name);
    run.maps.push_back(feature_map(model, p, s.index, s.lo, s.hi, s.points));
    progress_done();
  }
  if (request.geometry) run.geometry = evaluator::shape_geometry(run.declared, derive.set);
  return run;
}

SensitivityReportInput SensitivityRun::input() const {
  SensitivityReportInput in{model_path, model->info(), local,     visibility, global ? &global_result : nullptr,
                            sobol,      range_text,    maps};
  if (geometry) in.geometry = &*geometry;
  return in;
}

int run_sensitivity(int argc, char** argv) {
  CLI::App app{
      "How the model's modes depend on its parameters: local (normalized) sensitivities of each mode's "
      "frequency and damping ratio, which channel sees each mode best, Sobol indices over the parameters' "
      "ranges (--global), and feature maps of frequency against damping as one parameter sweeps (--sweep).",
      "mbgen sensitivity"};
  std::string model_path, json_path, report_dir;
  std::vector<std::string> sets, sweeps;
  bool global = false, bounds = false;
  double spread = 0.2;
  SobolOptions sobol;
  app.add_option("model", model_path, "model file (.mdl)")->required();
  app.add_flag("--global", global, "Sobol first-order and total indices (Saltelli/Jansen) over the parameters' ranges");
  app.add_option("--samples", sobol.samples, "--global: base samples N; N (k + 2) modal analyses (default 1024)")
      ->check(CLI::Range(16, 1 << 22));
  app.add_option("--seed", sobol.seed, "--global: seed of the samples (default 1)")->check(seed_check());
  app.add_option("--spread", spread,
                 "--global: each estimate parameter over value * [1 - S, 1 + S] within its bounds (default 0.2)")
      ->check(CLI::Range(1e-9, 10.0));
  app.add_flag("--bounds", bounds, "--global: over the parameters' declared bounds instead (they must be finite)");
  app.add_option("--sweep", sweeps, "feature map: NAME=LO:HI:N sweeps parameter NAME over N values (repeatable)");
  app.add_option("--set", sets, "override a parameter's value: NAME=VALUE (repeatable)");
  RoleOptions roles;
  add_role_options(app, roles);
  app.add_option("--json", json_path, "write the result (schema mbgen-sensitivity/1); - for standard output");
  app.add_option("--report", report_dir, "write a report directory (Markdown with plots)");
  app.set_version_flag("--version", version_text());
  return run_guarded(app, argc, argv, [&] {
    if (!global && (bounds || app.count("--samples") || app.count("--seed") || app.count("--spread")))
      throw CLI::ValidationError("--samples, --seed, --spread and --bounds need --global");
    OutputPlan plan;
    plan.files = {{"--json", json_path}};
    plan.report_dir = report_dir;
    plan.inputs = {model_path};
    plan.check();
    SensitivityRequest request;
    request.model_path = model_path;
    request.set = parse_set_options(sets);
    request.roles = roles;
    request.global = global;
    request.bounds = bounds;
    request.spread = spread;
    request.sobol = sobol;
    request.sweeps = sweeps;
    request.geometry = !report_dir.empty();  // the report draws the modes on it
    const SensitivityRun run = sensitivity_analysis(std::move(request));
    const SensitivityReportInput in = run.input();
    OutputFiles out;
    if (!json_path.empty()) out.add(json_path, sensitivity_json(in));
    if (!report_dir.empty()) write_sensitivity_report(out.stage_directory(report_dir), in);
    out.commit();
    if (json_path != "-") std::cout << sensitivity_summary(in);
    return 0;
  }, &model_path);
}

}  // namespace mbgen::cli
