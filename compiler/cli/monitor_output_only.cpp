// `mbgen monitor --output-only --data S1.csv --data S2.csv ... [--baseline K] [--model M.mdl]`: each record's modes
// by SSI-cov, tracked, the conditions' effect removed, a T^2 chart
// (runtime/include/mbgen/monitoring/operational_monitor.hpp).
#include "cli/monitor_output_only.hpp"

#include <mbgen/data/data_error.hpp>
#include <mbgen/data/data_set.hpp>
#include <mbgen/monitoring/measurement_time.hpp>
#include <mbgen/monitoring/operating_conditions.hpp>
#include <mbgen/monitoring/operational_explanation.hpp>
#include <mbgen/monitoring/operational_report.hpp>

#include <iostream>
#include <optional>
#include <stdexcept>

#include "cli/command_runs.hpp"
#include "cli/commands.hpp"
#include "cli/load_data.hpp"
#include "cli/output_files.hpp"
#include "evaluator/symbolic_evaluator.hpp"

namespace mbgen::cli {

namespace {

// One record's modes by SSI-cov, with its channels (which every set must share).
OperationalSet identify_set(const std::string& path, const OperationalRequest& request,
                            std::vector<std::string>& channels) {
  DataSet file = read_data_file(path);
  if (file.is_frf())
    throw DataError(path, 0, 0, "monitoring in operation needs time records of responses, but this holds FRFs "
                                "(leave out --output-only)");
  std::vector<TimeRecord> records;
  records.push_back(std::get<TimeRecord>(std::move(file.content)));
  const ResponseData data = response_data(records, request.selection);
  if (channels.empty()) channels = data.channels;
  if (data.channels != channels)
    throw DataError(path, 0, 0, "its responses differ from the first data set's: every set must have the same");
  OperationalSet set;
  set.file = path;
  try {
    set.modes = identify_output_only(data, request.identification).modes;
  } catch (const std::invalid_argument& e) {  // records too short for the lags, too few channels
    throw DataError(path, 0, 0, e.what());
  }
  return set;
}

}  // namespace

OperationalRun monitor_output_only(const OperationalRequest& request) {
  OperationalRun run;
  // Time order (as `monitor`), then the conditions of each file in that order.
  std::vector<std::optional<MeasurementTime>> stamps;
  for (const std::string& path : request.data_paths) stamps.push_back(read_measurement_time(path));
  std::vector<std::string> paths;
  std::vector<std::optional<std::string>> times;
  for (std::size_t i : time_order(request.data_paths, stamps)) {
    paths.push_back(request.data_paths[i]);
    times.push_back(stamps[i] ? std::optional<std::string>(stamps[i]->text) : std::nullopt);
  }
  std::vector<std::vector<ConditionValue>> lines;
  for (const std::string& path : paths) lines.push_back(read_operating_conditions(path));
  const ConditionTable conditions = condition_table(paths, lines);

  std::vector<OperationalSet> sets;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    OperationalSet set = identify_set(paths[i], request, run.channels);
    set.time = times[i];
    set.conditions = conditions.values[i];
    std::cerr << "monitor: data set " << i << "/" << paths.size() << " " << paths[i] << ": " << set.modes.size()
              << " modes\n";
    sets.push_back(std::move(set));
  }
  try {
    run.result = monitor_operational(sets, conditions.names, request.options);
    OperationalMonitorOptions plain = request.options;
    plain.compensate = false;
    if (request.options.compensate) run.raw = monitor_operational(sets, conditions.names, plain);
  } catch (const std::invalid_argument& e) {
    throw DataError(e.what());
  }

  run.compensated = request.options.compensate;
  run.method = output_only_method_name(request.identification.method);
  if (!request.model_path.empty()) {
    symbolic::DeriveOptions derive;
    derive.set = parse_set_options(request.sets);
    const ir::ModelIr declared = read_model_with_roles(request.model_path, request.roles, derive.set).model;
    const auto model = evaluator::make_evaluator(declared, derive);
    try {
      run.model_modes = operational_model_modes(*model, model->info().default_values(), run.channels, run.result);
    } catch (const std::invalid_argument& e) {
      throw DataError(request.model_path + ": " + e.what());
    }
    run.model_path = request.model_path;
    for (const OperationalChange& c : run.result.changes)
      run.explanations.push_back(explain_change(*run.model_modes, run.result, c));
  }
  return run;
}

OperationalReportInput OperationalRun::input() const {
  return {result, channels, method, compensated ? &raw : nullptr, model_path, model_modes ? &*model_modes : nullptr,
          explanations};
}

int run_monitor_output_only(const OperationalRequest& request) {
  const OperationalRun run = monitor_output_only(request);
  const OperationalReportInput in = run.input();
  OutputFiles out;
  if (!request.json_path.empty()) out.add(request.json_path, operational_monitor_json(in));
  if (!request.report_dir.empty()) write_operational_monitor_report(out.stage_directory(request.report_dir), in);
  out.commit();
  if (request.json_path != "-") std::cout << operational_monitor_summary(in);
  return 0;
}

}  // namespace mbgen::cli
