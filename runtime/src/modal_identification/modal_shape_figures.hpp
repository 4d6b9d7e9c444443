// The modal report's mode shapes against a model (modal_report.cpp): each identified mode's measured shape at the
// model's sensor points beside the paired model mode, at those points and on the model's whole geometry.
// Internal header.
#pragma once

#include "mbgen/modal_identification/modal_report.hpp"
#include "mbgen/report/report_document.hpp"

#include <string>

namespace mbgen {

// Adds the section and writes its SVG files to `dir`; nothing without a model, its geometry, or identified modes.
void add_identified_mode_figures(report::Document& doc, const std::string& dir, const ModalReportInput& in);

}  // namespace mbgen
