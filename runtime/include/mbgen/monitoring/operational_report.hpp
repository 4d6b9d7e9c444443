// Output of `monitor --output-only`: the `mbgen-monitor-operational/1` JSON (docs/interfaces.md) and a report
// directory with the trends of the tracked frequencies (raw and compensated) and the T^2 chart.
#pragma once

#include "mbgen/monitoring/operational_explanation.hpp"
#include "mbgen/monitoring/operational_monitor.hpp"

#include <optional>
#include <string>
#include <vector>

namespace mbgen {

struct OperationalReportInput {
  const OperationalMonitorResult& result;
  std::vector<std::string> channels;  // the responses
  std::string method;                 // of the identification: "ssi-cov"
  // The same series without compensation (its T^2 and limit), to show what the conditions alone do; may be null.
  const OperationalMonitorResult* uncompensated = nullptr;
  std::string model;                         // --model's file, empty without
  const OperationalModelModes* model_modes = nullptr;
  std::vector<ChangeExplanation> explanations;  // per change, with a model
};

// Deterministic (keys sorted, numbers in shortest round-trip form; NaN as null).
std::string operational_monitor_json(const OperationalReportInput& in);

// One line per change (or "no change detected") after a line on the chart.
std::string operational_monitor_summary(const OperationalReportInput& in);

// Writes DIR/report.md and report.html, frequencies.svg (per tracked mode raw and compensated against the set),
// t2.svg (the chart with its limit, the uncompensated one beside it when given), conditions.svg (when there are
// conditions); *.dat and *.gp beside them. Throws FitError if DIR cannot be written.
void write_operational_monitor_report(const std::string& dir, const OperationalReportInput& in);

}  // namespace mbgen
