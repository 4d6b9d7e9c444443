// `mbgen fit --method arx-two-stage`: the two-stage identification of Hamad et al., Tikrit J. Eng. Sci. 31(2), 2024
// (docs/methods.md, section "arx-two-stage").
//
//   FitResult r = mbgen::fit_arx_two_stage(model, records, options, ArxTwoStageOptions{});
//
// Stage 1: a linear regression (ARX) model of the coordinates q from the records, q_t = sum_i A_i q_{t-i} +
// sum_i E_i u_{t-i}, fitted by least squares (the paper trains Adaline units, whose minimum is this solution).
// Stage 2: the ARX model's free response from chosen initial conditions (each coordinate displaced, each given a
// velocity), its velocities and accelerations by finite differences, F = Z' Z^+ in the paper's transposed form
// F^T = (Z^T)^+ Z'^T (a least-squares problem of the order of 2n, not of the number of instants), C = -M F_1,
// K = -M F_2 with the mass matrix known, modal frequencies and damping ratios. Stage 3 (ours): the estimated
// parameters whose K(p), C(p) reproduce those matrices, by least squares over the model's parameterisation
// (analytic derivatives).
//
// Needs every coordinate measured as a displacement (the outputs in the records, through the model's output
// matrix, determine q) and the mass matrix known (no estimated parameter in M). Refuses otherwise with a FitError
// naming what is missing.
#pragma once

#include "mbgen/estimation/fit.hpp"

namespace mbgen {

struct ArxTwoStageOptions {
  // Past samples of q in the regression. 2 is the exact order of a sampled system whose every coordinate is
  // measured (x_k = [q_k; q_k'] follows from q_k and q_{k-1}); the paper's Houbolt form has 3, which on exact data
  // makes the regressors linearly dependent (the paper's Sec. 3.1, "lack of a single solution").
  int lags = 2;
  // Samples of each free response of stage 2 (the paper found 50 to 500 points equivalent).
  int free_response_samples = 500;
};

// method "arx-two-stage". FitResult: the parameters (no std: the method's error is the bias of the least-squares
// ARX fit under output noise, which grows with the noise, and no variance estimate of it is honest), the
// output-error cost and NRMSE of a simulation at the estimate, method_details["arx_two_stage"]: the identified
// K and C matrices, the ARX fit's residual, and the modes (frequencies and damping ratios from F; the paper's
// modal damping ratios from the undamped modes of M and K).
FitResult fit_arx_two_stage(const Model& model, const std::vector<DataSet>& data, const FitOptions& options = {},
                            const ArxTwoStageOptions& arx = {});

}  // namespace mbgen
