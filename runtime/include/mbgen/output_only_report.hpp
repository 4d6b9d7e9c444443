// Output of `mbgen modal --output-only`: the `mbgen-modal/1` JSON with the output-only members (docs/interfaces.md,
// docs/modal.md), a report directory, and the terminal's mode table.
#pragma once

#include <string>

#include "mbgen/output_only_modal.hpp"

namespace mbgen {

struct OutputOnlyReportInput {
  const ResponseData& data;
  const OutputOnlyIdentification& result;
  const OutputOnlyOptions& options;
  const FddResult* spectrum = nullptr;  // the singular values behind SSI-cov's stabilization diagram (report only)
};

// Keys sorted, numbers in shortest round-trip form: the same input gives the same bytes.
std::string output_only_json(const OutputOnlyReportInput& in);

// DIR/report.md and report.html: settings, the mode table, the stabilization diagram over the spectral matrix's
// singular values (SSI-cov) or those singular values with the peaks (FDD), the auto-MAC. DIR must exist.
void write_output_only_report(const std::string& dir, const OutputOnlyReportInput& in);

std::string output_only_summary(const OutputOnlyReportInput& in);

}  // namespace mbgen
