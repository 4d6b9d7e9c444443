// Driving points whose measured phase a passive structure cannot have: evidence about the measurement chain that
// needs the model's geometry but no fit (mbgen/residuals/chain_scores.hpp, driving_point_passivity). `fit` and
// `diagnose` warn about them first; the diagnosis also fits the polarity candidates they point to, whatever a fit that
// could not follow the reversed data says (docs/diagnosis.md, "The measurement chain").
#pragma once

#include <mbgen/residuals/chain_scores.hpp>
#include <mbgen/data/data_set.hpp>

#include <string>
#include <vector>

#include "ir/model_ir.hpp"

namespace mbgen::diagnosis {

// An output at a force input's point, along its direction (the same frame, and the same point and direction as
// written once the front end has filled them), whose measured FRF gives out power on more than half of the lines
// where its phase is clear: the force or the sensor is recorded with the wrong sign.
struct ReversedDrivingPoint {
  std::string output, input, file;
  PassivityCheck check;
};

// One per such channel and FRF data set.
std::vector<ReversedDrivingPoint> reversed_driving_points(const ir::ModelIr& model, const std::vector<DataSet>& data);

// "a5/F in tws.csv is a driving point (...), but on 100 % of the 373 lines where its phase is clear it gives out
// power, which a passive structure cannot: the force F or the sensor a5 is recorded with the wrong sign"
std::string describe(const ReversedDrivingPoint& point);

}  // namespace mbgen::diagnosis
