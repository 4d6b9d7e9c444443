// The geometry a model's mode shapes are drawn on (runtime/include/mbgen/report/mode_shape_svg.hpp), from its model
// file: the bodies' centres of mass, the outputs' sensor points, the elements' ends and the elements between them, at
// the parameter values (`set` overrides them, as --set does), with each point's translation per unit of each body
// coordinate. The translations are the rows the derivation builds the output map and the elements from
// (symbolic::displacement_rows: the linearized u + theta x r of the point's body), evaluated at the values.
#pragma once

#include <mbgen/report/mode_shape_svg.hpp>

#include <map>
#include <string>

#include "ir/model_ir.hpp"

namespace mbgen::evaluator {

// Throws frontend::ModelError for bad overrides or a point that is not a number at the values.
ShapeGeometry shape_geometry(const ir::ModelIr& model, const std::map<std::string, std::string>& set = {});

}  // namespace mbgen::evaluator
