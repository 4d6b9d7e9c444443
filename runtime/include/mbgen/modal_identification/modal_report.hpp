// Output of `mbgen modal`: the `mbgen-modal/1` JSON (docs/interfaces.md, extended in docs/modal.md) and a report
// directory with Markdown and gnuplot plots.
#pragma once

#include <optional>
#include <string>

#include "mbgen/modal_identification/modal_identification.hpp"
#include "mbgen/modal_identification/modal_pairing.hpp"
#include "mbgen/report/mode_shape_svg.hpp"

namespace mbgen {

struct ModelComparison {
  std::string model_file;
  ModelModes modes;
  ModePairing pairing;
};

// What a modal analysis produced, for its outputs.
struct ModalReportInput {
  const ModalData& data;
  const ModalIdentification& result;
  const ModalOptions& options;
  const ModelComparison* model = nullptr;  // with --model
  std::string quantity_source;             // how the quantity was learned: "UFF ordinate type", "--quantity", ...
  const ShapeGeometry* geometry = nullptr;  // the model's, with --model: the report draws the shapes on it
};

// The JSON document: keys sorted, numbers in shortest round-trip form, deterministic.
std::string modal_result_json(const ModalReportInput& in);

// Writes DIR/report.md and DIR/report.html with the mode table, the stabilization diagram over the sum of the FRFs'
// magnitudes, the auto-MAC (and with a model the MAC against its modes), and per channel the synthesized against the
// measured FRF, and with a model's geometry the measured shapes at its sensor points beside the paired model modes
// (modal_shape_figures.cpp); plots as gnuplot scripts and data beside SVGs rendered when gnuplot is installed. DIR
// must exist.
// Throws std::runtime_error when a file cannot be written.
void write_modal_report(const std::string& dir, const ModalReportInput& in);

// A plain-text mode table for the terminal.
std::string modal_summary(const ModalReportInput& in);

}  // namespace mbgen
