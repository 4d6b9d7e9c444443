// Checks of measured data that need the model's geometry but no fit, run by `fit` and `diagnose` before they fit:
// what the summary, the JSON (`warnings`) and the report say first.
#pragma once

#include <mbgen/data_set.hpp>

#include <string>
#include <vector>

#include "ir/model.hpp"

namespace mbgen::cli {

// Driving points whose phase a passive structure cannot have (mbgen/chain_scores.hpp, driving_point_passivity): an
// output at a force input's point, along its direction (the same frame, and the same point and direction as written
// once the front end has filled them), whose measured FRF gives out power on more than half of the lines where its
// phase is clear. The force or the sensor is then recorded with the wrong sign: no fit of the structure can follow
// it. One warning per such channel and data set.
std::vector<std::string> passivity_warnings(const ir::ModelIr& model, const std::vector<DataSet>& data);

}  // namespace mbgen::cli
