// `mbgen modal --output-only --data REC.csv [--data ...] [--method ssi-cov|fdd]`: the responses of time records,
// no force (runtime/include/mbgen/modal_identification/output_only_modal.hpp, docs/modal.md).
#include "cli/modal_output_only.hpp"

#include <mbgen/data/data_error.hpp>
#include <mbgen/data/data_set.hpp>
#include <mbgen/methods/operational_update.hpp>
#include <mbgen/modal_identification/output_only_report.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "cli/commands.hpp"
#include "cli/load_data.hpp"
#include "cli/output_files.hpp"
#include "evaluator/symbolic_evaluator.hpp"

namespace mbgen::cli {

namespace {

// --update: the modes' uncertainties from data blocks, then the model fitted to them.
OperationalUpdate update_model(const OutputOnlyRequest& request, const ResponseData& data,
                               const OutputOnlyIdentification& id, const OutputOnlyOptions& options) {
  symbolic::DeriveOptions derive;
  derive.set = parse_set_options(request.sets);
  const ir::ModelIr declared = read_model_with_roles(request.model_path, request.roles, derive.set).model;
  const auto model = evaluator::make_evaluator(declared, derive);
  try {
    model_outputs_of(model->info(), data.channels);
  } catch (const std::invalid_argument& e) {
    throw DataError(data.files.front(), 0, 0, std::string(e.what()) + " (" + request.model_path + ")");
  }
  BlockUncertainty uncertainty;
  try {
    uncertainty = block_uncertainty(data, id, options);
  } catch (const std::invalid_argument& e) {  // blocks too short for the lags
    throw DataError(data.files.front(), 0, 0,
                    std::string("--update: the data blocks of the uncertainties: ") + e.what());
  }
  std::vector<OperationalTarget> targets;
  for (std::size_t m = 0; m < id.modes.size(); ++m) {
    const OperationalMode& mode = id.modes[m];
    const ModeUncertainty& u = uncertainty.modes[m];
    targets.push_back({mode.f_hz, mode.zeta, mode.shape, u.f_std_hz, u.zeta_std, u.shape_std});
  }
  OperationalUpdate update = update_from_operational_modes(*model, data.channels, targets);
  update.model_file = request.model_path;
  update.uncertainty = std::move(uncertainty);
  return update;
}

// A warning for each FDD mode whose damping is not determined (EFDD's note says why: e.g. lines too coarse for its
// half-power band), so that a missing damping ratio is not read past in the table.
std::string damping_warnings(const OutputOnlyReportInput& in) {
  const OutputOnlyIdentification& r = in.result;
  if (r.method != OutputOnlyMethod::Fdd || in.setups || r.fdd.peaks.size() != r.modes.size()) return {};
  std::string text;
  for (std::size_t m = 0; m < r.modes.size(); ++m)
    if (!std::isfinite(r.modes[m].zeta)) {
      char f[32];
      std::snprintf(f, sizeof f, "%.4f", r.modes[m].f_hz);
      const std::string& note = r.fdd.peaks[m].note;
      const std::string what = "damping not determined";
      text += "warning: mode " + std::to_string(m + 1) + " (" + f + " Hz): " +
              (note.rfind(what, 0) == 0 ? note : note.empty() ? what : what + " (" + note + ")") + "\n";
    }
  return text;
}

// The JSON and the report, whole or not at all, then the summary and the warnings (on standard error when the JSON
// went to standard output).
int write_output_only(const OutputOnlyRequest& request, const OutputOnlyReportInput& in) {
  OutputFiles out;
  if (!request.json_path.empty()) out.add(request.json_path, output_only_json(in));
  if (!request.report_dir.empty()) write_output_only_report(out.stage_directory(request.report_dir), in);
  out.commit();
  if (request.json_path != "-")
    std::cout << output_only_summary(in) << damping_warnings(in);
  else
    std::cerr << damping_warnings(in);
  return 0;
}

// FRFs given to --output-only --method fdd: read as the spectra of unmeasured white forces at their inputs, a
// check of FDD/EFDD on measured data (docs/modal.md).
int run_output_only_frfs(const OutputOnlyRequest& request, const std::vector<FrfData>& frfs) {
  if (!request.model_path.empty())
    throw DataError(request.data_paths.front(), 0, 0, "--update needs time records of responses, not FRFs");
  if (!request.selection.ignore.empty())
    throw DataError(request.data_paths.front(), 0, 0, "--ignore applies to time records, not FRFs");
  const ModalData data = modal_data(frfs, {});
  OutputOnlyIdentification id;
  try {
    id = identify_output_only_frfs(data, request.options);
  } catch (const std::invalid_argument& e) {  // lines not on the multiples of their spacing
    throw DataError(request.data_paths.front(), 0, 0, e.what());
  }
  const ResponseData responses = frf_responses(data);
  const OutputOnlyReportInput in{responses, id, request.options, nullptr, nullptr, nullptr};
  return write_output_only(request, in);
}

}  // namespace

int run_output_only(const OutputOnlyRequest& request) {
  std::vector<TimeRecord> records;
  std::vector<FrfData> frfs;
  for (const std::string& path : request.data_paths) {
    DataSet file = read_data_file(path);
    if (file.is_frf() && request.options.method != OutputOnlyMethod::Fdd)
      throw DataError(path, 0, 0, "output-only modal analysis needs time records of responses for SSI-cov, but "
                                  "this holds FRFs (--method fdd reads them as the spectra of an unmeasured white "
                                  "force; or leave out --output-only)");
    if (file.is_frf() ? !records.empty() : !frfs.empty())
      throw DataError(path, 0, 0, std::string("output-only modal analysis takes time records or FRFs, not both: "
                                              "this holds ") + (file.is_frf() ? "FRFs" : "a time record"));
    if (file.is_frf())
      frfs.push_back(std::get<FrfData>(std::move(file.content)));
    else
      records.push_back(std::get<TimeRecord>(std::move(file.content)));
  }
  if (!frfs.empty()) return run_output_only_frfs(request, frfs);
  std::vector<ResponseData> setups = response_setups(records, request.selection);
  OutputOnlyOptions options = request.options;
  options.ssi.progress = [](int order, int max_order) {
    progress_line("modal: order " + std::to_string(order) + "/" + std::to_string(max_order));
  };
  // One setup, or several (roving sensors with shared references) identified one by one and merged.
  std::optional<MergedSetups> merged;
  OutputOnlyIdentification single;
  FddResult spectrum;  // the report's background for SSI-cov (the first setup's)
  try {
    if (setups.size() == 1)
      single = identify_output_only(setups.front(), options);
    else
      merged = identify_setups(setups, options);  // a setup's error names its file (DataError)
    if (!request.report_dir.empty() && options.method == OutputOnlyMethod::SsiCov)
      spectrum = fdd(setups.front(), options.fdd);
  } catch (const std::invalid_argument& e) {  // records too short for the lags, too few channels for the order
    progress_done();
    throw DataError(setups.front().files.front(), 0, 0, e.what());
  }
  progress_done();
  std::optional<OperationalUpdate> update;
  if (!request.model_path.empty()) {
    if (merged)
      throw DataError(setups.back().files.front(), 0, 0,
                      "--update needs the records of one setup (these responses differ from the first record's)");
    progress_line("modal: the model against the modes");
    try {
      update = update_model(request, setups.front(), single, options);
    } catch (...) {
      progress_done();  // the message on a line of its own
      throw;
    }
    progress_done();
  }
  const OutputOnlyReportInput in{merged ? merged->data : setups.front(), merged ? merged->result : single, options,
                                 options.method == OutputOnlyMethod::SsiCov ? &spectrum : nullptr,
                                 merged ? &*merged : nullptr, update ? &*update : nullptr};
  return write_output_only(request, in);
}

}  // namespace mbgen::cli
