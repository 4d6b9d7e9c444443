// Output of `mbgen modal --output-only`: the `mbgen-modal/1` JSON with the output-only members (docs/interfaces.md,
// docs/modal.md), a report directory, and the terminal's mode table.
#pragma once

#include <string>

#include "mbgen/modal_identification/operational_comparison.hpp"
#include "mbgen/modal_identification/output_only_modal.hpp"

namespace mbgen {

struct OutputOnlyReportInput {
  const ResponseData& data;
  const OutputOnlyIdentification& result;
  const OutputOnlyOptions& options;
  const FddResult* spectrum = nullptr;  // the singular values behind SSI-cov's stabilization diagram (report only)
  const MergedSetups* setups = nullptr;  // several setups: `data` and `result` are the merged ones
  const OperationalUpdate* update = nullptr;  // --model --update: the model fitted to the modes
};

// The run whose diagram, spectrum and settings the outputs show: the first setup's when setups were merged.
inline const OutputOnlyIdentification& method_run(const OutputOnlyReportInput& in) {
  return in.setups ? in.setups->per_setup.front() : in.result;
}

// Keys sorted, numbers in shortest round-trip form: the same input gives the same bytes.
std::string output_only_json(const OutputOnlyReportInput& in);

// DIR/report.md and report.html: settings, the mode table, the stabilization diagram over the spectral matrix's
// singular values (SSI-cov) or those singular values with the peaks (FDD), the auto-MAC. DIR must exist.
void write_output_only_report(const std::string& dir, const OutputOnlyReportInput& in);

std::string output_only_summary(const OutputOnlyReportInput& in);

}  // namespace mbgen
