// `mbgen modal --output-only`: operational modal analysis of response time records (docs/modal.md).
#pragma once

#include <string>
#include <vector>

#include "cli/parameter_roles.hpp"

#include <mbgen/modal_identification/output_only_modal.hpp>

namespace mbgen::cli {

struct OutputOnlyRequest {
  std::vector<std::string> data_paths;
  ResponseSelection selection;  // --ignore, --references
  OutputOnlyOptions options;    // --method, --max-order
  std::string json_path, report_dir;
  // --model with --update: the model fitted to the identified modes (docs/modal.md).
  std::string model_path;
  std::vector<std::string> sets;
  RoleOptions roles;
};

// Reads the records, identifies the modes and writes the outputs (whole or not at all); returns the exit status.
// Throws as the other commands do (DataError naming the file for bad records).
int run_output_only(const OutputOnlyRequest& request);

}  // namespace mbgen::cli
