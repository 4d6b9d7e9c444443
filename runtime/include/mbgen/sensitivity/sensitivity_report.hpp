// Output of `mbgen sensitivity`: the `mbgen-sensitivity/1` JSON (docs/sensitivity.md), a report directory with
// Markdown and gnuplot plots, and a terminal summary.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mbgen/report/mode_shape_svg.hpp"
#include "mbgen/sensitivity/sensitivity.hpp"

namespace mbgen {

struct SensitivityReportInput {
  std::string model_file;
  const ModelInfo& info;
  const LocalSensitivity& local;
  const ModeVisibility& visibility;
  const GlobalSensitivity* global = nullptr;  // with --global
  SobolOptions sobol;
  std::string range_text;        // how the ranges were chosen, for the report
  std::vector<FeatureMap> maps;  // one per --sweep
  const ShapeGeometry* geometry = nullptr;  // where known: the modes are drawn on it
};

// Keys sorted, numbers in shortest round-trip form (NaN as null); deterministic.
std::string sensitivity_json(const SensitivityReportInput& in);
// Writes DIR/report.md and DIR/report.html (tables, heat maps, mode shapes with a geometry, feature maps), the plots as gnuplot scripts and data
// beside SVGs rendered when gnuplot is installed. DIR must exist. Throws std::runtime_error when a file cannot be
// written.
void write_sensitivity_report(const std::string& dir, const SensitivityReportInput& in);
std::string sensitivity_summary(const SensitivityReportInput& in);

}  // namespace mbgen
