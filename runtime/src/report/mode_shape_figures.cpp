#include "mbgen/report/mode_shape_figures.hpp"

#include "mbgen/report/report_files.hpp"

#include <algorithm>
#include <filesystem>

namespace mbgen {

report::Inline mode_shape_legend() {
  return "Each mode drawn on the model's geometry in three orthographic views (x-y, x-z, y-z), one scale for the "
         "three: the bodies' centres of mass (dots, named), the sensor points of the outputs (squares), the "
         "elements' ends (small dots) and the elements as lines between them, an end on a ground as a hatched "
         "anchor. Grey: at rest. Red: the mode, each point moved by its body's translation and small rotation "
         "(u + theta x r, r from the centre of mass to the point), the largest translation drawn as 20 % of the "
         "model's size (the largest extent of its points; a length of 1 when they all sit at one place). A "
         "complex shape is drawn at the instant its largest translation peaks (turned by one phase, real part).";
}

void add_model_mode_figures(report::Document& doc, const std::string& dir, const std::string& stem,
                            const ShapeGeometry& geometry, const std::vector<std::string>& titles,
                            const Eigen::MatrixXcd& shapes) {
  for (std::size_t m = 0; m < std::min(titles.size(), kMaxModePictures); ++m) {
    const std::string file = stem + "_" + std::to_string(m + 1) + ".svg";
    write_report_file((std::filesystem::path(dir) / file).string(),
                      model_mode_svg(geometry, titles[m], shapes.col(static_cast<Eigen::Index>(m))));
    doc.figure(file, report::text(titles[m]));
  }
  if (titles.size() > kMaxModePictures)
    doc.paragraph(report::Inline("The first ") << kMaxModePictures << " of " << titles.size()
                                               << " modes are drawn; the others are not.");
}

}  // namespace mbgen
