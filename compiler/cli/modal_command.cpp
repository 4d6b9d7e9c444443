// `mbgen modal --data FILE [--data FILE ...] [--band LO:HI] [--model MODEL.mdl] [--json OUT] [--report DIR]
// [--uff OUT.uff] [--synthesis OUT.uff|OUT.csv]`:
// experimental modal analysis of measured FRFs (runtime/include/mbgen/modal_identification/modal_identification.hpp,
// docs/modal.md); with --output-only, of response records (cli/modal_output_only.cpp).
#include <mbgen/data/data_error.hpp>
#include <mbgen/data/data_set.hpp>
#include <mbgen/modal_identification/modal_report.hpp>

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/command_runs.hpp"
#include "cli/commands.hpp"
#include "cli/load_data.hpp"
#include "cli/modal_output_only.hpp"
#include "cli/modal_synthesis.hpp"
#include "cli/output_files.hpp"
#include "cli/number_checks.hpp"
#include "cli/parameter_roles.hpp"
#include "cli/run_guarded.hpp"
#include "cli/uff_modes.hpp"
#include "cli/version.hpp"
#include "evaluator/shape_geometry.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"

namespace mbgen::cli {

namespace {
constexpr int kMaxOutputOnlyOrder = 400;
}  // namespace

ModalRun modal_identification(ModalRequest request) {
  ModalRun run;
  std::string& quantity_source = run.quantity_source;
  std::unique_ptr<Model> model;
  if (!request.model_path.empty()) {
    symbolic::DeriveOptions derive;
    derive.set = parse_set_options(request.sets);
    run.declared.emplace(frontend::parse_file(request.model_path));
    model = evaluator::make_evaluator(*run.declared, derive);
  }
  std::vector<FrfData> frfs;
  FrfQuantity quantity = FrfQuantity::Unknown;
  for (std::size_t d = 0; d < request.data_paths.size(); ++d) {
    const std::string& path = request.data_paths[d];
    DataSet file = model ? read_data_file(path, model->info().inputs, model->info().outputs) : read_data_file(path);
    if (!file.is_frf())
      throw DataError(path, 0, 0,
                      "modal analysis needs FRFs, but this is a time record (--output-only analyses response records)");
    frfs.push_back(std::get<FrfData>(std::move(file.content)));
    // From the records as read: by the file's name it missed UFF on standard input, through a pipe or under
    // another extension (the modes and their std then differed), and it read the file a second time.
    const FrfQuantity here = uff_frf_quantity(frfs.back());
    quantity = d == 0 || here == quantity ? here : FrfQuantity::Unknown;
  }
  if (quantity != FrfQuantity::Unknown) quantity_source = "from the UFF ordinate type";
  if (request.quantity != "auto") {
    quantity = request.quantity == "receptance" ? FrfQuantity::Receptance
               : request.quantity == "mobility" ? FrfQuantity::Mobility
                                             : FrfQuantity::Accelerance;
    quantity_source = "given by --quantity";
  }
  run.options = std::move(request.options);
  ModalData& data = run.data;
  data = modal_data(frfs, request.band, quantity);

  std::optional<ModelComparison>& comparison = run.comparison;
  if (model) {
    comparison.emplace();
    comparison->model_file = request.model_path;
    comparison->modes = model_modes(*model, model->info().default_values(), data);
    if (data.quantity == FrfQuantity::Unknown && comparison->modes.quantity != FrfQuantity::Unknown) {
      data.quantity = comparison->modes.quantity;
      quantity_source = "from the model's outputs";
    }
  }

  ModalIdentification& result = run.result;
  try {
    result = identify_modes(data, run.options);
  } catch (const std::invalid_argument& e) {  // an order or a selected frequency the data cannot serve
    progress_done();
    throw DataError(request.data_paths.front(), 0, 0, e.what());
  }
  progress_done();
  if (comparison) comparison->pairing = pair_modes(result.modes, comparison->modes);

  return run;
}

int run_modal(int argc, char** argv) {
  CLI::App app{
      "Experimental modal analysis of measured FRFs, no model needed: poles by the (poly-reference) "
      "least-squares complex-frequency method over a range of orders, a stabilization diagram, automatic "
      "selection of the physical poles and their refinement, residues by LSFD with residual terms, and a mode table.",
      "mbgen modal"};
  std::vector<std::string> data_paths, sets;
  std::string band_text, model_path, json_path, report_dir, uff_path, synthesis_path, quantity_text = "auto";
  ModalOptions options;
  app.add_option("--data", data_paths,
                 "measured FRFs: CSV or UFF 58/58b; repeatable (same frequency lines); with --output-only time "
                 "records of responses (records with other responses are setups, merged on shared references)")
      ->required();
  app.add_option("--band", band_text, "analyse LO <= f <= HI only (Hz; either side may be left empty)");
  app.add_option("--model", model_path,
                 "pair the identified modes with this model's modes by MAC (.mdl); with --output-only and --update, "
                 "fit it to them");
  app.add_option("--set", sets, "with --model: override a parameter's value, NAME=VALUE (repeatable)");
  app.add_option("--json", json_path, "write the result (schema mbgen-modal/1); - for standard output");
  app.add_option("--report", report_dir,
                 "write a report directory (Markdown with the stabilization diagram, MAC, FRFs)");
  app.add_option("--uff", uff_path,
                 "write the modes as UFF 55 (complex shapes at the measured nodes and directions, UFF 15 nodes where "
                 "known) and OUT.map beside it naming the points");
  app.add_option("--synthesis", synthesis_path,
                 "write the FRFs synthesized from the modes with their residual terms (what channel_error and the "
                 "report's overlays compare) on the analysed lines, named as the measured channels: OUT.uff or "
                 "OUT.unv (UFF 58, with OUT.map beside it) or OUT.csv");
  app.add_option("--max-order", options.lscf.max_order,
                 "highest model order (default: from the data, about 64 / references; with --output-only the "
                 "states of SSI-cov, default 48)")
      ->check(positive_number());
  app.add_option("--select", options.select_hz,
                 "use the poles nearest these frequencies [Hz] instead of the automatic choice")
      ->delimiter(',')
      ->check(positive_number());
  bool no_refine = false;
  app.add_flag("--no-refine", no_refine, "keep the LSCF poles (cluster medians) instead of refining them");
  app.add_option("--quantity", quantity_text,
                 "what the FRFs are: auto (from a UFF file's ordinate type or the model's outputs), receptance, "
                 "mobility or accelerance")
      ->check(CLI::IsMember({"auto", "receptance", "mobility", "accelerance"}));
  // Output-only (operational) modal analysis of response records: docs/modal.md.
  bool output_only = false;
  std::string method_text;
  OutputOnlyRequest oma;
  app.add_flag("--output-only", output_only,
               "operational modal analysis: the data are time records of responses, no force (SSI-cov or FDD)");
  app.add_option("--method", method_text, "with --output-only: ssi-cov (default) or fdd")
      ->check(CLI::IsMember({"ssi-cov", "fdd"}));
  app.add_option("--references", oma.selection.references,
                 "with --output-only: the reference responses of SSI-cov's correlations (default: all)")
      ->delimiter(',');
  app.add_option("--ignore", oma.selection.ignore,
                 "with --output-only: signals that are not responses (e.g. a measured force), left out with a note")
      ->delimiter(',');
  bool update = false;
  app.add_flag("--update", update,
               "with --output-only and --model: fit the model's mass, stiffness and damping parameters to the "
               "identified frequencies, shapes and damping ratios, weighted by their uncertainties from data blocks");
  add_role_options(app, oma.roles);
  app.set_version_flag("--version", version_text());
  return run_guarded(app, argc, argv, [&] {
    if (!output_only && update) throw CLI::ValidationError("--update", "needs --output-only and --model");
    if (!update && !oma.roles.empty())
      throw CLI::ValidationError(!oma.roles.fix.empty() ? "--fix" : !oma.roles.free.empty() ? "--free" : "--bound",
                                 "needs --output-only --update");
    if (output_only) {
      if (update && model_path.empty()) throw CLI::ValidationError("--update", "needs --model");
      if (!update && !model_path.empty())
        throw CLI::ValidationError("--model", "with --output-only only with --update (the model fitted to the modes)");
      if (!update && !sets.empty()) throw CLI::ValidationError("--set", "not with --output-only without --update");
      if (update && method_text == "fdd")
        throw CLI::ValidationError("--update", "SSI-cov only (its modes' uncertainties come from data blocks)");
      for (const auto& [given, option] : {std::pair{!band_text.empty(), "--band"},
                                          {!options.select_hz.empty(), "--select"},
                                          {no_refine, "--no-refine"}, {quantity_text != "auto", "--quantity"},
                                          {!uff_path.empty(), "--uff"}, {!synthesis_path.empty(), "--synthesis"}})
        if (given) throw CLI::ValidationError(option, "not with --output-only (FRF analysis only)");
      oma.data_paths = data_paths;
      oma.options.method = method_text == "fdd" ? OutputOnlyMethod::Fdd : OutputOnlyMethod::SsiCov;
      oma.options.ssi.max_order = options.lscf.max_order;
      if (oma.options.method == OutputOnlyMethod::Fdd && options.lscf.max_order > 0)
        throw CLI::ValidationError("--max-order", "SSI-cov only (not with --method fdd)");
      // FDD decomposes the full spectral matrix: every channel is a reference.
      if (oma.options.method == OutputOnlyMethod::Fdd && !oma.selection.references.empty())
        throw CLI::ValidationError("--references", "SSI-cov only (not with --method fdd)");
      // The block Toeplitz matrix grows with the order: 400 states is ~200 modes, and an SVD of minutes.
      if (options.lscf.max_order > kMaxOutputOnlyOrder)
        throw CLI::ValidationError("--max-order", "at most " + std::to_string(kMaxOutputOnlyOrder) +
                                                      " with --output-only");
      oma.json_path = json_path;
      oma.report_dir = report_dir;
      oma.model_path = model_path;
      oma.sets = sets;
      OutputPlan plan;
      plan.files = {{"--json", json_path}};
      plan.report_dir = report_dir;
      plan.inputs = data_paths;
      if (!model_path.empty()) plan.inputs.push_back(model_path);
      plan.check();
      return run_output_only(oma);
    }
    for (const auto& [given, option] : {std::pair{!method_text.empty(), "--method"},
                                        {!oma.selection.references.empty(), "--references"},
                                        {!oma.selection.ignore.empty(), "--ignore"}})
      if (given) throw CLI::ValidationError(option, "needs --output-only");
    options.refine = !no_refine;
    FrequencyBand band;
    if (!band_text.empty()) {
      const Band b = parse_band("--band", band_text);
      band = {b.lo, b.hi};
    }
    if (!sets.empty() && model_path.empty()) throw CLI::ValidationError("--set", "needs --model");
    OutputPlan plan;
    if (uff_path == "-")
      throw CLI::ValidationError("--uff", "a UFF file comes with its mapping file (OUT.map): name a file");
    const std::optional<DataFormat> synthesis_named = data_format_of(synthesis_path);
    if (!synthesis_path.empty() && !synthesis_named)
      throw CLI::ValidationError("--synthesis", "the name says the format: OUT.uff or OUT.unv (UFF 58) or OUT.csv, "
                                                "got `" + synthesis_path + "`");
    const DataFormat synthesis_format = synthesis_named.value_or(DataFormat::Csv);
    const bool synthesis_uff = !synthesis_path.empty() && synthesis_format == DataFormat::Uff;
    plan.files = {{"--json", json_path},
                  {"--uff", uff_path},
                  {"--uff (its mapping file)", uff_path.empty() ? "" : uff_path + ".map"},
                  {"--synthesis", synthesis_path},
                  {"--synthesis (its mapping file)", synthesis_uff ? synthesis_path + ".map" : ""}};
    plan.report_dir = report_dir;
    plan.inputs = data_paths;
    if (!model_path.empty()) plan.inputs.push_back(model_path);
    plan.check();

    ModalRequest request;
    request.data_paths = data_paths;
    request.band = band;
    request.model_path = model_path;
    request.sets = sets;
    request.options = options;
    request.options.lscf.progress = [](int order, int max_order) {
      progress_line("modal: order " + std::to_string(order) + "/" + std::to_string(max_order));
    };
    request.quantity = quantity_text;
    const ModalRun run = modal_identification(std::move(request));
    ModalReportInput in = run.input();
    std::optional<ShapeGeometry> geometry;  // the report draws the shapes on the model's
    if (run.declared && !report_dir.empty())
      in.geometry = &geometry.emplace(evaluator::shape_geometry(*run.declared, parse_set_options(sets)));
    OutputFiles out;
    if (!json_path.empty()) out.add(json_path, modal_result_json(in));
    if (!report_dir.empty()) write_modal_report(out.stage_directory(report_dir), in);
    if (!synthesis_path.empty()) {
      const DataTexts synthesis = synthesis_texts(run.data, run.result, synthesis_format, data_paths,
                                                  run.declared ? &*run.declared : nullptr, parse_set_options(sets));
      out.add(synthesis_path, synthesis.data);
      if (synthesis_uff) out.add(synthesis_path + ".map", synthesis.mapping);
    }
    if (!uff_path.empty()) {
      const std::optional<ir::ModelIr> model =
          model_path.empty() ? std::nullopt : std::optional<ir::ModelIr>(frontend::parse_file(model_path));
      const UffText uff = identified_modes_uff(run.data, run.result, data_paths, model ? &*model : nullptr,
                                               parse_set_options(sets));
      out.add(uff_path, uff.data);
      out.add(uff_path + ".map", uff.mapping);
    }
    out.commit();
    if (json_path != "-") std::cout << modal_summary(in);
    return 0;
  }, &model_path);
}

}  // namespace mbgen::cli
