// `mbgen monitor --output-only`: monitoring in operation from response records alone (docs/monitor.md,
// "Monitoring in operation").
#pragma once

#include <string>
#include <vector>

#include <mbgen/monitoring/operational_monitor.hpp>
#include <mbgen/modal_identification/output_only_modal.hpp>

#include "cli/parameter_roles.hpp"

namespace mbgen::cli {

struct OperationalRequest {
  std::vector<std::string> data_paths;
  ResponseSelection selection;         // --references, --ignore
  OutputOnlyOptions identification;    // --max-order (SSI-cov)
  OperationalMonitorOptions options;   // --baseline, --false-alarm, --environmental-components, --no-compensation
  std::string model_path;              // --model
  std::vector<std::string> sets;       // --set (with --model)
  RoleOptions roles;
  std::string json_path, report_dir;
};

// Reads and orders the records (`# time=`), reads their `# condition` lines, identifies each set's modes, monitors
// them and writes the outputs (whole or not at all); returns the exit status. Throws DataError naming the file for
// bad records or condition lines, CLI::ValidationError for bad combinations.
int run_monitor_output_only(const OperationalRequest& request);

}  // namespace mbgen::cli
