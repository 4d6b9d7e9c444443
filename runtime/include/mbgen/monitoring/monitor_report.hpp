// Output of `monitor`: the `mbgen-monitor/1` JSON (docs/interfaces.md) and a report directory with Markdown and
// gnuplot trend plots.
#pragma once

#include "mbgen/monitoring/monitor.hpp"

#include <string>

namespace mbgen {

// The JSON document, deterministic (keys sorted, numbers in shortest round-trip form).
std::string monitor_result_json(const MonitorResult& result);

// Writes DIR/report.md and DIR/report.html with the changes, the series table, and per monitored parameter a trend plot
// (estimates with their 2-std bars, the reference level with its 2-sigma scatter band, the changes marked) plus the
// misfit's trend; *.dat and *.gp beside them, rendered to SVG when gnuplot is installed. Throws FitError if DIR cannot
// be written.
void write_monitor_report(const std::string& dir, const MonitorResult& result);

}  // namespace mbgen
