// `mbgen diagnose MODEL.mdl --data FILE [--data FILE ...] [--method NAME] [--json OUT.json] [--report DIR]
// [--extended OUT.mdl]`:
// what the model gets wrong, which extension explains it, and the extended model with its generated code.
#include <iostream>
#include <sstream>

#include "cli/command_runs.hpp"
#include "cli/commands.hpp"
#include "cli/data_checks.hpp"
#include "cli/parameter_roles.hpp"
#include "cli/load_data.hpp"
#include "cli/method_option.hpp"
#include "cli/output_files.hpp"
#include "cli/number_checks.hpp"
#include "cli/run_guarded.hpp"
#include "cli/seed_option.hpp"
#include "cli/starts_option.hpp"
#include "cli/version.hpp"
#include "diagnosis/engine/diagnose.hpp"
#include "diagnosis/engine/diagnosis_json.hpp"
#include "diagnosis/engine/diagnosis_report.hpp"
#include "emit/cpp_emitter.hpp"
#include "emit/cxx_text.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"

#include <mbgen/residuals/data_split.hpp>

namespace mbgen::cli {

namespace {

// Findings listed on standard output; a long list goes on in the JSON and the report.
constexpr std::size_t kSummaryFindings = 8;
// Findings listed under each selected extension as those it explains.
constexpr std::size_t kSummaryExplained = 3;

std::string summary(const diagnosis::DiagnosisResult& r) {
  std::ostringstream out;
  for (const std::string& w : r.warnings) out << "warning: " << w << "\n";
  out << "verdict: " << r.verdict << "\n";
  // Each selected extension with what it says and which findings it explains.
  const std::vector<Discrepancy>& nominal_findings = r.nominal.residual.discrepancies;
  for (std::size_t i = 0; i < r.selected.size(); ++i) {
    out << "selected: " << r.selected[i] << "\n";
    if (i < r.described.size() && !r.described[i].empty())
      out << "  " << r.described[i] << "\n";
    if (i >= r.explains.size()) continue;
    if (r.explains[i].empty()) {
      out << "  " << diagnosis::kExplainsNoFindingAlone << "\n";
      continue;
    }
    out << "  it explains:\n";
    for (std::size_t k = 0; k < r.explains[i].size() && k < kSummaryExplained; ++k)
      out << "    - " << diagnosis::reader_text(r, nominal_findings[r.explains[i][k]].text) << "\n";
    if (r.explains[i].size() > kSummaryExplained)
      out << "    ... and " << r.explains[i].size() - kSummaryExplained << " more (--json, --report)\n";
  }
  if (!r.nominal.fit.converged)
    out << "warning: the nominal model's fit did not converge (" << r.nominal.fit.stop_reason
        << "): some findings may be the fit's, not the model's\n";
  // The strongest findings (they come strongest first); the rest are in the JSON and the report.
  const std::vector<Discrepancy>& findings = r.nominal.residual.discrepancies;
  if (!findings.empty()) out << "what the nominal model gets wrong:\n";
  for (std::size_t k = 0; k < findings.size() && k < kSummaryFindings; ++k)
    out << "  - " << diagnosis::reader_text(r, findings[k].text) << "\n";
  if (findings.size() > kSummaryFindings)
    out << "  ... and " << findings.size() - kSummaryFindings << " more (--json, --report)\n";
  if (r.verdict == "extended" && !r.final.residual.discrepancies.empty()) {
    out << "still unexplained after extension:\n";
    for (const Discrepancy& d : r.final.residual.discrepancies)
      out << "  - " << diagnosis::reader_text(r, d.text) << "\n";
  }
  return out.str();
}

std::string base_name(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

// OUT.mdl -> OUT_model.cpp / OUT_model.hpp beside it.
std::string sibling(const std::string& mdl, const std::string& suffix) {
  const std::size_t dot = mdl.find_last_of('.'), slash = mdl.find_last_of('/');
  const std::string stem = dot == std::string::npos || (slash != std::string::npos && dot < slash) ? mdl : mdl.substr(0, dot);
  return stem + suffix;
}

// The method's estimate as a start of the nominal fit: run on the part of the data that fit sees (within --fit-band,
// the held-back validation part left out), so the validation stays data the nominal model was not fitted to.
std::map<std::string, double> method_start(const ir::ModelIr& model, const symbolic::DeriveOptions& derive,
                                           const std::vector<DataSet>& data, const diagnosis::DiagnoseOptions& options,
                                           const MethodDescriptor& method, MethodOptions method_options) {
  const auto evaluator = evaluator::make_evaluator(model, derive);
  const SplitData split = split_for_validation(options.fit_data ? *options.fit_data : data);
  method_options.analytical_solver = analytical_solver(model, derive);
  const FitResult estimate = run_method(method, {*evaluator, split.fit, options.fit, method_options});
  std::cerr << "diagnose: start from --method " << method.name << ": its estimate (nrmse " << estimate.nrmse
            << ") starts the nominal fit\n";
  return estimate_as_start(*evaluator, estimate);
}


}  // namespace

DiagnoseRun diagnose_model(DiagnoseRequest request) {
  diagnosis::DiagnoseOptions& options = request.options;
  // The text is read once (standard input cannot be read twice): the model is parsed from it.
  const RoledModel roled = read_model_with_roles(request.model_path, request.roles, options.set);
  const std::string& text = roled.text;
  const ir::ModelIr& model = roled.model;
  symbolic::DeriveOptions derive;
  derive.set = options.set;
  const std::vector<DataSet> data =
      load_data(request.data_paths, evaluator::make_evaluator(model, derive)->info(), model, derive.set);
  if (!request.fit_band.empty()) options.fit_data = within_band(data, parse_band("--fit-band", request.fit_band));
  DiagnoseRun run;
  const MethodDescriptor& method = method_named(request.method, "diagnose");
  check_method_takes(method, data);
  if (!method.output_error) {
    add_start(method_start(model, derive, data, options, method, request.method_options), options.fit);
  }
  run.result = diagnosis::diagnose(model, text, data, options);
  if (!method.output_error) run.result.start_method = method.name;
  run.result.warnings = passivity_warnings(model, data);
  run.set = derive.set;
  return run;
}

std::string diagnose_run_json(const DiagnoseRun& run, const std::string& extended_model_path) {
  return diagnosis::diagnosis_json(run.result, extended_model_path);
}

int run_diagnose(int argc, char** argv) {
  CLI::App app{"Fit the model, find what its simulation gets wrong beyond the noise, try extensions of the model "
               "built from its own structure, and keep one only on strong evidence.",
               "mbgen diagnose"};
  std::string model_path, json_path, report_dir, extended_path, fit_band;
  std::vector<std::string> data_paths, sets;
  diagnosis::DiagnoseOptions options;
  app.add_option("model", model_path, "model file (.mdl); - reads standard input")->required();
  app.add_option("--data", data_paths, "measured data: CSV (time or FRF) or UFF 58; repeatable")->required();
  app.add_option("--json", json_path, "write the result (schema mbgen-diagnosis/1); - for standard output");
  app.add_option("--report", report_dir, "write a report directory (Markdown with plots)");
  app.add_option("--extended", extended_path,
                 "when extended, write the extended model here (and its C++ as OUT_model.cpp/.hpp beside it)");
  app.add_option("--set", sets, "override a parameter's value: NAME=VALUE (repeatable)");
  RoleOptions roles;
  add_role_options(app, roles);
  app.add_option("--starts", options.fit.starts, "starts of the nominal fit's global search (default 16)")
      ->check(starts_range());
  app.add_option("--seed", options.fit.seed, "seed of the global searches (default 1)")->check(seed_check());
  bool no_modal_start = false;
  app.add_flag("--no-start-from-modes", no_modal_start, "the nominal fit does not start where the model's modes match "
               "the data's own (by default it does, beside its random starts; docs/estimation.md)");
  app.add_option("--full-fits", options.full_fits,
                 "candidates fitted fully after the screening (default 4; 0: every candidate)")
      ->check(non_negative_number());
  std::string method = "auto";
  MethodOptions method_options;
  add_method_choice(app, method, "an estimation method whose estimate is one more start of the nominal fit, which "
                                 "then judges by output error as always: ");
  add_method_own_options(app, method_options);
  app.add_option("--fit-band", fit_band,
                 "fit the models on the FRF lines within LO:HI Hz only (the band the model is meant to represent), "
                 "and judge them over all the data");
  app.set_version_flag("--version", version_text());
  return run_guarded(app, argc, argv, [&] {
    options.set = parse_set_options(sets);
    options.start_from_modes = !no_modal_start;
    if (extended_path == "-")
      throw CLI::ValidationError("--extended", "the extended model and its C++ are files; name one");
    if (!extended_path.empty())
      if (const std::string problem = emit::include_name_problem(base_name(sibling(extended_path, "_model.hpp")));
          !problem.empty())
        throw CLI::ValidationError("--extended", "its C++ header cannot be named in an #include line: " + problem);
    OutputPlan plan;
    plan.files = {{"--json", json_path},
                  {"--extended", extended_path},
                  {"--extended (its C++ source)", extended_path.empty() ? "" : sibling(extended_path, "_model.cpp")},
                  {"--extended (its C++ header)", extended_path.empty() ? "" : sibling(extended_path, "_model.hpp")}};
    plan.report_dir = report_dir;
    plan.inputs = data_paths;
    plan.inputs.push_back(model_path);
    plan.check();
    DiagnoseRequest request;
    request.model_path = model_path;
    request.data_paths = data_paths;
    request.roles = roles;
    request.options = options;
    request.options.progress = [](const std::string& line) {
      progress_done();
      std::cerr << "diagnose: " << line << "\n";
    };
    request.options.fit.progress = [](const FitProgress& p) {
      progress_line("  fit: " + p.stage + " start " + std::to_string(p.start + 1) + "/" + std::to_string(p.starts) +
                    ", iteration " + std::to_string(p.iteration));
    };
    request.fit_band = fit_band;
    request.method = method;
    request.method_options = method_options;
    const DiagnoseRun run = diagnose_model(std::move(request));
    progress_done();
    const diagnosis::DiagnosisResult& result = run.result;
    symbolic::DeriveOptions derive;
    derive.set = run.set;

    OutputFiles out;
    const bool extended = result.verdict == "extended";
    if (extended && !extended_path.empty()) {
      out.add(extended_path, result.final.text);
      const ir::ModelIr ext = frontend::parse_string(result.final.text, extended_path);
      emit::CppEmitOptions cpp;
      cpp.header_file = sibling(extended_path, "_model.hpp");
      cpp.source_file = sibling(extended_path, "_model.cpp");
      cpp.model_file = extended_path;
      const emit::CppEmitResult code = emit::emit_cpp(symbolic::derive(ext, derive), cpp);
      out.add(cpp.header_file, code.header);
      out.add(cpp.source_file, code.source);
    }
    if (!json_path.empty()) out.add(json_path, diagnose_run_json(run, extended ? extended_path : ""));
    if (!report_dir.empty()) diagnosis::write_diagnosis_report(out.stage_directory(report_dir), result);
    out.commit();
    if (json_path != "-") std::cout << summary(result);
    return 0;
  }, &model_path);
}

}  // namespace mbgen::cli
