// A model updated to output-only modes (docs/modal.md, "A model against output-only modes").
//
//   OperationalUpdate u = mbgen::update_from_operational_modes(model, channels, targets, options);
//
// 1. The model's modes at the response channels (C v) paired with the identified ones by MAC at the priors, and
//    again at every evaluation (greedy, one to one).
// 2. The mass/stiffness parameters by Levenberg-Marquardt on a log scale (the modal method's solver, modal_solve)
//    of the weighted residuals (f_model - f) / f_std and the shape left after the best complex factor / shape_std.
//    Unscaled shapes and frequencies are unchanged when every mass and stiffness is multiplied by one factor, so a
//    problem whose Jacobian at the priors has that direction (or any other) in its null space is refused, naming
//    the parameters and --fix.
// 3. The damping parameters by least squares on the identified damping ratios (rows divided by zeta_std) at the
//    fitted masses and stiffnesses.
// Standard deviations: Gauss-Newton, (J^T J)^-1 of the weighted residuals at the estimate, not rescaled by the
// misfit (the weights are the identified modes' own standard deviations); for the dampings (Q^T Q)^-1 of the
// weighted ratios, at fixed masses and stiffnesses.
#pragma once

#include "mbgen/estimation/fit.hpp"
#include "mbgen/modal_identification/operational_comparison.hpp"

#include <string>
#include <vector>

namespace mbgen {

// `targets` without a finite standard deviation are left out (listed in `unpaired`). The estimated parameters are
// FitOptions::estimate or the model's Estimate role (candidate_parameters). Throws FitError ("modal: error: ...")
// for a parameter the modes cannot serve (acting on the output map, on M/K and C at once), a rank-deficient
// problem (the common factor of masses and stiffnesses above all), no pairable mode, a model that cannot be
// evaluated; std::invalid_argument for a channel that is not a model output.
OperationalUpdate update_from_operational_modes(const Model& model, const std::vector<std::string>& channels,
                                                const std::vector<OperationalTarget>& targets,
                                                const FitOptions& options = {});

}  // namespace mbgen
