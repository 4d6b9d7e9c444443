// `mbgen monitor MODEL.mdl --data FILE [--data FILE ...] [--baseline N] [--json OUT] [--report DIR]`: one machine
// measured again and again; each data set fitted, changes of its parameters detected against a baseline, and a
// structural change (one no parameter explains) diagnosed (runtime/include/mbgen/monitoring/monitor.hpp,
// docs/monitor.md). `mbgen monitor --manifest FLEET.csv --out DIR [--item I | --count]`: many machines, each an
// idempotent item (fleet_manifest.hpp, docs/fleets.md).
// `mbgen monitor --output-only --data REC.csv ...`: response records alone, in operation (monitor_output_only.cpp).
#include <mbgen/monitoring/measurement_time.hpp>
#include <mbgen/monitoring/monitor_report.hpp>

#include <mbgen/report/report_files.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/command_runs.hpp"
#include "cli/commands.hpp"
#include "cli/parameter_roles.hpp"
#include "cli/fleet_manifest.hpp"
#include "cli/monitor_output_only.hpp"
#include "cli/load_data.hpp"
#include "cli/method_option.hpp"
#include "cli/output_files.hpp"
#include "cli/run_guarded.hpp"
#include "cli/seed_option.hpp"
#include "cli/starts_option.hpp"
#include "cli/version.hpp"
#include <mbgen/residuals/channel_residuals.hpp>
#include "diagnosis/engine/diagnose.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/message.hpp"
#include "frontend/parser.hpp"

namespace mbgen::cli {

namespace {

std::string summary(const MonitorResult& r) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line,
                "%zu data sets, baseline %d; CUSUM k %.3g, h %.4g, single-set limit %.4g (one false alarm in %.6g sets)\n",
                r.series.size(), r.baseline, r.k, r.h, r.single_set_limit, r.run_length);
  out += line;
  if (r.changes.empty()) out += "no change detected\n";
  for (const MonitorChange& c : r.changes) {
    out += "change at data set " + std::to_string(c.index) + (c.time ? " (" + *c.time + ")" : "") + ": ";
    // A structural change's cause first; the parameters it moved are what the fit bent towards it.
    if (c.structural)
      out += "structural, cause " + (c.cause.empty() ? std::string("not found") : c.cause) +
             (c.parameters.empty() ? "" : "; moved in the fit: ");
    for (std::size_t i = 0; i < c.parameters.size(); ++i) out += (i ? ", " : "") + c.parameters[i];
    out += "\n  " + c.text + "\n";
  }
  return out;
}

// How badly a fitted model explains one data set, on the scale of its noise: the diagnosis's residual analysis
// (measured vs model FRFs, a time record through Welch H1) gives the mean normalized residual over all lines, about
// 1 where only noise remains (the noise level is estimated from each data set itself, frf_noise.hpp). It is a
// continuous statistic with a small scatter (on mdof2's 40 dB series 0.95 to 1.07 in plain noise; a loose wall
// 1.4 to 1.8). The strongest finding's significance was tried first: a finding in plain noise (a two-line dip,
// mean normalized residual 4) came in about one set in eight and gave four times the baseline's misfit, as large
// as the loose wall's own findings.
double residual_misfit(const Model& model, const DataSet& set, const FitResult& fit, const FrfWeighting& weighting) {
  const std::vector<ChannelResidual> channels = channel_residuals(model, {set}, fit.values, weighting);
  return analyse_residuals(channels).mean_z;
}

}  // namespace

// Monitors one machine: its model (path, or "-" for standard input) and its data sets, ordered by time.
MonitorResult monitor_machine(const std::string& model_path, const std::vector<std::string>& data_paths,
                              MonitorSettings settings) {
  MonitorOptions& options = settings.options;
  const std::vector<std::string>& sets = settings.sets;
  const bool no_diagnosis = settings.no_diagnosis;
  // The text is read once (standard input cannot be read twice): the model is parsed from it.
  symbolic::DeriveOptions derive;
  derive.set = parse_set_options(sets);
  const RoledModel roled = read_model_with_roles(model_path, settings.roles, derive.set);
  const std::string& text = roled.text;
  const ir::ModelIr& parsed = roled.model;
  const auto evaluator = evaluator::make_evaluator(parsed, derive);

  std::vector<std::optional<MeasurementTime>> stamps;
  for (const std::string& path : data_paths) stamps.push_back(read_measurement_time(path));
  const std::vector<std::size_t> order = time_order(data_paths, stamps);
  std::vector<std::string> ordered_paths;
  std::vector<std::optional<std::string>> times;
  for (std::size_t i : order) {
    ordered_paths.push_back(data_paths[i]);
    times.push_back(stamps[i] ? std::optional<std::string>(stamps[i]->text) : std::nullopt);
  }
  const std::vector<DataSet> data = load_data(ordered_paths, evaluator->info(), parsed, derive.set);
  if (static_cast<int>(data.size()) <= options.baseline)
    throw CLI::ValidationError("--data", "monitoring needs more data sets than the baseline's " +
                                             std::to_string(options.baseline) + " (--baseline)");

  // --method: the method's estimate on each set is one more start of that set's fit (the fit's own options, without
  // the chosen starts of the series, run the method).
  const MethodDescriptor& method = method_named(settings.method, "monitor");
  check_method_takes(method, data);
  if (!method.output_error) {
    settings.method_options.analytical_solver = analytical_solver(parsed, derive);
    options.add_starts = [&method, &evaluator, &settings, fit = options.fit](const DataSet& set, FitOptions& fo) {
      const std::vector<DataSet> one{set};
      add_start(estimate_as_start(*evaluator, run_method(method, {*evaluator, one, fit, settings.method_options})), fo);
    };
  }
  const FrfWeighting weighting = options.fit.frf_weighting;
  options.misfit = [&](const DataSet& set, const FitResult& fit) {
    return residual_misfit(*evaluator, set, fit, weighting);
  };
  options.fit.progress = [](const FitProgress& p) {
    progress_line("  fit: " + p.stage + " start " + std::to_string(p.start + 1) + "/" + std::to_string(p.starts) +
                  ", iteration " + std::to_string(p.iteration));
  };
  options.progress = [](const MonitorProgress& p) {
    if (p.stage == "fitting") return;
    progress_done();
    std::cerr << "monitor: data set " << p.index << "/" << p.count << " " << p.file << ": " << p.stage << "\n";
  };
  MonitorResult result = monitor(*evaluator, data, times, options);
  result.model = model_path;
  if (!method.output_error) result.start_method = method.name;

  // A structural change: the diagnosis of that data set against the model names the cause where it can.
  for (MonitorChange& change : result.changes) {
    if (!change.structural || no_diagnosis) continue;
    std::cerr << "monitor: diagnosing data set " << change.index << " (a structural change)\n";
    diagnosis::DiagnoseOptions dopts;
    dopts.set = derive.set;
    dopts.fit.starts = options.warm_starts;
    dopts.fit.seed = options.fit.seed;
    for (const MonitoredParameter& p : result.parameters) dopts.fit.also_start_at[p.name] = p.mean;
    dopts.fit.progress = options.fit.progress;
    const diagnosis::DiagnosisResult d =
        diagnosis::diagnose(parsed, text, {data[static_cast<std::size_t>(change.index)]}, dopts);
    progress_done();
    if (d.verdict == "extended" && !d.selected.empty()) {
      change.cause = d.selected.front();
      const std::string description = d.described.empty() || d.described.front().empty()
                                          ? std::string()
                                          : " (" + d.described.front() + ")";
      change.text = "The diagnosis names the cause: " + change.cause + description + ". " + change.text;
    } else {
      change.text += " The diagnosis named no cause (verdict " + d.verdict + ")";
      std::vector<const diagnosis::CandidateOutcome*> leads;
      for (const diagnosis::CandidateOutcome& c : d.candidates)
        if (c.round == 1 && c.qualifies) leads.push_back(&c);
      std::stable_sort(leads.begin(), leads.end(), [](auto* a, auto* b) { return a->delta_bic < b->delta_bic; });
      for (std::size_t i = 0; i < leads.size(); ++i) {
        change.qualified.push_back(leads[i]->id);
        char gain[64];
        std::snprintf(gain, sizeof gain, "%.4g", leads[i]->delta_bic);
        change.text += (i ? ", " : "; qualified on their own but not confirmed: ") + leads[i]->id + " (BIC " + gain + ")";
      }
      change.text += ".";
    }
  }

  return result;
}

namespace {

// Everything a fleet item's result depends on, one fact per line: when it equals the digest written with the item's
// last result, the item is up to date.
std::string item_digest(const FleetItem& item, const MonitorSettings& s) {
  std::ostringstream d;
  d << version_text() << "\n"
    << "baseline " << s.options.baseline << ", run-length " << s.options.run_length << ", structural-ratio "
    << s.options.structural_ratio << ", starts " << s.options.fit.starts << ", warm-starts " << s.options.warm_starts
    << ", seed " << s.options.fit.seed << (s.no_diagnosis ? ", no diagnosis" : "") << "\n";
  // A method adds to the digest only where it changes the result (not output error: the fits are those without it).
  if (!method_named(s.method, "monitor").output_error)
    d << "method " << s.method << method_options_digest(s.method_options) << "\n";
  std::vector<std::string> sets = s.sets;
  std::sort(sets.begin(), sets.end());
  for (const std::string& set : sets) d << "set " << set << "\n";
  d << "model " << item.model << " " << file_digest(item.model) << "\n";
  for (const std::string& f : item.data) d << "data " << f << " " << file_digest(f) << "\n";
  return d.str();
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return in ? text.str() : std::string();
}

// Runs one item of a fleet into OUT/MACHINE unless its digest says the result there is current. Returns true when
// it ran.
bool run_fleet_item(const FleetItem& item, const std::string& out_dir, const MonitorSettings& settings) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(out_dir) / item.machine;
  const std::string digest = item_digest(item, settings);
  std::error_code ec;
  if (fs::exists(dir / "monitor.json", ec) && read_text_file((dir / "inputs.digest").string()) == digest) {
    std::cerr << "monitor: " << item.machine << ": up to date\n";
    return false;
  }
  std::cerr << "monitor: " << item.machine << ": " << item.data.size() << " data sets\n";
  OutputPlan plan;
  plan.report_dir = dir.string();
  plan.inputs = item.data;
  plan.inputs.push_back(item.model);
  plan.check();
  MonitorResult result = monitor_machine(item.model, item.data, settings);
  OutputFiles out;
  const fs::path staged = out.stage_directory(dir.string());
  write_report_file((staged / "monitor.json").string(), monitor_result_json(result));
  write_monitor_report((staged / "report").string(), result);
  write_report_file((staged / "inputs.digest").string(), digest);
  out.commit();
  std::cout << item.machine << ": " << summary(result);
  return true;
}

}  // namespace

int run_monitor(int argc, char** argv) {
  CLI::App app{"Fit each of a machine's data sets in time order, learn the parameters' scatter from a baseline, and "
               "report when and which parameters changed (a CUSUM with a stated false-alarm rate), or that the model "
               "no longer fits (a structural change, then diagnosed). With --manifest, a fleet of machines as "
               "independent items for a batch engine (docs/fleets.md).",
               "mbgen monitor"};
  std::string model_path, json_path, report_dir, manifest_path, item_selector, out_dir;
  std::vector<std::string> data_paths;
  MonitorSettings settings;
  MonitorOptions& options = settings.options;
  bool count = false;
  app.add_option("model", model_path, "model file (.mdl); - reads standard input (not with --manifest)");
  app.add_option("--data", data_paths,
                 "measured data sets: CSV (time or FRF) or UFF 58; repeatable, ordered by their `# time=` lines "
                 "(argument order when none has one)");
  app.add_option("--baseline", options.baseline, "the first N data sets are the baseline (default 3, at least 2)")
      ->check(CLI::Range(2, 1000000));
  app.add_option("--run-length", options.run_length,
                 "average number of data sets between false alarms of the whole test (default 1000)")
      ->check(CLI::Range(2.0, 1e12));
  app.add_option("--structural-ratio", options.structural_ratio,
                 "a data set whose mean normalized residual exceeds this many times the baseline's largest is a "
                 "structural change (default 1.25)")
      ->check(CLI::Range(1.0001, 1e6));
  app.add_option("--json", json_path, "write the result (schema mbgen-monitor/1); - for standard output");
  app.add_option("--report", report_dir, "write a report directory (Markdown with parameter trend plots)");
  app.add_option("--set", settings.sets, "override a parameter's value: NAME=VALUE (repeatable)");
  add_role_options(app, settings.roles);
  app.add_option("--starts", options.fit.starts, "starts of the first data set's fit (default 16)")
      ->check(starts_range());
  app.add_option("--warm-starts", options.warm_starts,
                 "starts of each later, warm-started fit (default 4: the previous estimate, the priors, 2 random; at most --starts)")
      ->check(starts_range());
  app.add_option("--seed", options.fit.seed, "seed of the global searches (default 1)")->check(seed_check());
  app.add_flag("--no-diagnosis", settings.no_diagnosis, "report a structural change without running the diagnosis on it");
  add_method_choice(app, settings.method, "an estimation method whose estimate on each data set is one more start of "
                                          "that set's fit, which then judges by output error as always: ");
  add_method_own_options(app, settings.method_options);
  app.add_option("--manifest", manifest_path,
                 "a fleet: CSV `machine,model,data` (docs/fleets.md); each machine is an item written to OUT/MACHINE");
  app.add_option("--item", item_selector,
                 "with --manifest: run only this item, by 0-based index (a job array's index) or machine name");
  app.add_option("--out", out_dir, "with --manifest: the directory of the items' results");
  app.add_flag("--count", count, "with --manifest: print the number of items and exit");
  // Monitoring in operation: response records, no force (docs/monitor.md, "Monitoring in operation").
  bool output_only = false, no_compensation = false;
  OperationalRequest oma;
  app.add_flag("--output-only", output_only,
               "monitoring in operation: the data are response records (no force); modes by SSI-cov, tracked, the "
               "`# condition` variables' effect removed, a Hotelling T^2 chart");
  app.add_option("--model", oma.model_path,
                 "with --output-only: a model whose parameters' sensitivities explain a change (default values, --set)");
  app.add_option("--false-alarm", oma.options.false_alarm,
                 "with --output-only: the probability that a set without a change alarms (default 0.01)")
      ->check(CLI::Range(1e-9, 0.5));
  app.add_option("--environmental-components", oma.options.environmental_components,
                 "with --output-only and no `# condition` lines: principal components removed as environmental "
                 "(default: those with 90 % of the baseline's variance, at most modes - 1)")
      ->check(CLI::Range(0, 1000));
  app.add_flag("--no-compensation", no_compensation,
               "with --output-only: test the raw frequencies (to see what the conditions alone do)");
  app.add_option("--references", oma.selection.references,
                 "with --output-only: the reference responses of SSI-cov's correlations (default: all)")
      ->delimiter(',');
  app.add_option("--ignore", oma.selection.ignore,
                 "with --output-only: signals that are not responses (e.g. a measured force), left out")
      ->delimiter(',');
  app.add_option("--max-order", oma.identification.ssi.max_order,
                 "with --output-only: SSI-cov's highest model order (default 48)")
      ->check(CLI::Range(2, 400));
  app.set_version_flag("--version", version_text());
  return run_guarded(app, argc, argv, [&] {
    if (output_only) {
      if (!model_path.empty())
        throw CLI::ValidationError("model", "with --output-only a model is optional and given as --model M.mdl");
      for (const char* option : {"--run-length", "--structural-ratio", "--starts", "--warm-starts", "--seed",
                                 "--no-diagnosis", "--manifest", "--item", "--out", "--count", "--method"})
        if (app.count(option)) throw CLI::ValidationError(option, "not with --output-only");
      if (data_paths.empty()) throw CLI::ValidationError("--data", "at least one --data file is required");
      if (!settings.sets.empty() && oma.model_path.empty()) throw CLI::ValidationError("--set", "needs --model");
      if (!settings.roles.empty() && oma.model_path.empty())
        throw CLI::ValidationError("--fix", "--fix, --free and --bound need --model");
      oma.data_paths = data_paths;
      oma.options.baseline = app.count("--baseline") ? options.baseline : 0;
      oma.options.compensate = !no_compensation;
      oma.sets = settings.sets;
      oma.roles = settings.roles;
      oma.json_path = json_path;
      oma.report_dir = report_dir;
      OutputPlan plan;
      plan.files = {{"--json", json_path}};
      plan.report_dir = report_dir;
      plan.inputs = data_paths;
      if (!oma.model_path.empty()) plan.inputs.push_back(oma.model_path);
      plan.check();
      return run_monitor_output_only(oma);
    }
    for (const char* option : {"--model", "--false-alarm", "--environmental-components", "--no-compensation",
                               "--references", "--ignore", "--max-order"})
      if (app.count(option)) throw CLI::ValidationError(option, "needs --output-only");
    if (!manifest_path.empty()) {
      if (!model_path.empty() || !data_paths.empty() || !json_path.empty() || !report_dir.empty())
        throw CLI::ValidationError("--manifest", "the manifest names the models and data; MODEL, --data, --json and "
                                                 "--report are for one machine");
      const std::vector<FleetItem> items = read_fleet_manifest(manifest_path);
      if (count) {
        std::cout << items.size() << "\n";
        return 0;
      }
      if (out_dir.empty()) throw CLI::ValidationError("--out", "--manifest needs --out DIR for the items' results");
      const FleetItem* selected = item_selector.empty() ? nullptr : &select_fleet_item(items, item_selector);
      std::error_code ec;
      std::filesystem::create_directories(out_dir, ec);  // items of a job array may race here: that is harmless
      if (!std::filesystem::is_directory(out_dir, ec))
        throw OutputError(frontend::error_text(out_dir, "cannot create the directory"));
      if (selected) {
        run_fleet_item(*selected, out_dir, settings);
        return 0;
      }
      // Every item in turn; one that fails is reported and the others still run (rerun to retry: done items skip).
      int status = 0;
      for (const FleetItem& item : items) {
        try {
          run_fleet_item(item, out_dir, settings);
        } catch (...) {
          progress_done();
          std::cerr << "monitor: " << item.machine << " (" << manifest_path << ":" << item.line << ") failed:\n";
          status = std::max(status, report_current_exception());
        }
      }
      return status;
    }
    if (!item_selector.empty() || !out_dir.empty() || count)
      throw CLI::ValidationError("--item", "--item, --out and --count go with --manifest");
    if (model_path.empty()) throw CLI::ValidationError("model", "a model file is required (or --manifest)");
    if (data_paths.empty()) throw CLI::ValidationError("--data", "at least one --data file is required");
    OutputPlan plan;
    plan.files = {{"--json", json_path}};
    plan.report_dir = report_dir;
    plan.inputs = data_paths;
    plan.inputs.push_back(model_path);
    plan.check();
    MonitorResult result = monitor_machine(model_path, data_paths, settings);

    OutputFiles out;
    if (!json_path.empty()) out.add(json_path, monitor_result_json(result));
    if (!report_dir.empty()) write_monitor_report(out.stage_directory(report_dir), result);
    out.commit();
    if (json_path != "-") std::cout << summary(result);
    return 0;
  }, &model_path);
}

}  // namespace mbgen::cli
