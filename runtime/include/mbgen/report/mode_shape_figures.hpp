// A report's section of model mode shapes (mbgen/report/mode_shape_svg.hpp): one SVG file per mode in the report
// directory and a figure of it in the document, with the words that say what the pictures show.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

#include "mbgen/report/mode_shape_svg.hpp"
#include "mbgen/report/report_document.hpp"

namespace mbgen {

// What every mode-shape picture shows, for the paragraph before them.
report::Inline mode_shape_legend();

// At most this many pictures in one report: a machine-scale model has hundreds of modes, and a report of hundreds
// of pictures is read by nobody; the first ones (the lowest frequencies) are those a test sees.
inline constexpr std::size_t kMaxModePictures = 48;

// Writes DIR/STEM_1.svg, DIR/STEM_2.svg, ... (one per shape, columns of `shapes` over the model's coordinates, each
// titled by `titles`; the first kMaxModePictures, with a note of the rest) and adds a figure of each to `doc`.
// Throws FitError when a file cannot be written.
void add_model_mode_figures(report::Document& doc, const std::string& dir, const std::string& stem,
                            const ShapeGeometry& geometry, const std::vector<std::string>& titles,
                            const Eigen::MatrixXcd& shapes);

}  // namespace mbgen
