// The zero-pole comparison of an identified transfer function with the model's at the estimate, and the thesis's
// validation checks of the identified poles (Sec. 3.6.2, 4.7: rules 1-3, and poles the model has no counterpart
// for). Internal header.
//
// Checks per identified pole (the member with Im >= 0): unstable (Re >= 0); real (no vibration mode); overdamped
// (zeta > 0.3, rule 3); outside the band the data cover (rule 1: its coefficients rest on extrapolation); no model
// counterpart (no model pole within 5 % of it, |dlambda| / |lambda|); near-cancelled by an identified zero within
// one half-power bandwidth |Re lambda| in a channel (rule 2), in every channel: the data cannot determine it.
#pragma once

#include "coefficient_problem.hpp"
#include "model_coefficients.hpp"

#include <nlohmann/json.hpp>

namespace mbgen::methods {

struct Validation {
  nlohmann::json zero_pole;  // poles, zeros per channel, DC gains: identified beside model
  nlohmann::json checks;     // per pole: findings and verdict; the transfer function's verdict
  int suspect_poles = 0;
};

Validation validate(const StepOneTf& identified, const ModelTf& model);

}  // namespace mbgen::methods
