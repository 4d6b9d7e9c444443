// Checks of measured data that need the model's geometry but no fit, run by `fit` and `diagnose` before they fit:
// what the summary, the JSON (`warnings`) and the report say first.
#pragma once

#include <mbgen/data/data_set.hpp>

#include <string>
#include <vector>

#include "ir/model_ir.hpp"

namespace mbgen::cli {

// The warnings of diagnosis/engine/driving_points.hpp: one per driving point whose measured phase a passive
// structure cannot have (the force or the sensor recorded with the wrong sign), per data set.
std::vector<std::string> passivity_warnings(const ir::ModelIr& model, const std::vector<DataSet>& data);

}  // namespace mbgen::cli
