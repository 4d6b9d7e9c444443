// The thesis's "two step" method (Nickel 1999, Sec. 3.6.2, 4.5, 4.7, 5.3.4.1; docs/methods.md#two-step):
//
//   step one: a black-box continuous-time transfer function per input from the data, of the model's order
//             (2 nb poles for the nb coordinates of the input's excited block): from FRFs a rational fit with a
//             common denominator (Sanathanan-Koerner, then maximum likelihood); from a time record an ARX model,
//             its order chosen by AIC, BIC or FPE, its poles pruned by the thesis's rules to the model's order and
//             mapped to continuous time under the record's input hold;
//   step two: the physical parameters from the identified coefficients and the model's (transfer_function.hpp):
//             (c) minimisation of the normalised coefficient mismatch Q_TF = sum ((L_i(p) - L^_i) / L^_i)^2 over all
//             channels (Eq. 3.99), Levenberg-Marquardt within the parameters' bounds from a deterministic
//             multi-start; (b) where there are as many compared coefficients as parameters, Newton's method on the
//             coefficient equations L(p) = L^ (Eq. 3.92) from the same starts.
//
// The estimate's uncertainty propagates step one's coefficient covariance through step two's linearisation
// (sandwich); a step one without a covariance (ARX) gives std null. method_details holds both steps, the zero-pole
// comparison of identified and model transfer functions at the estimate and the validation checks (Sec. 4.7).
#pragma once

#include "mbgen/estimation/fit.hpp"
#include "mbgen/methods/two_step_analytical.hpp"

#include <string>

namespace mbgen {

struct TwoStepOptions {
  // Step two's route: "auto" (the analytical solution where `analytical` is given and finds an admissible one, else
  // Newton where the system is square and it finds an admissible root, else the minimisation), "analytical" (FitError
  // when it cannot: no solver, no closed form, no admissible real solution), "newton" (the numerical route; square
  // systems only, FitError otherwise) or "minimisation".
  std::string solver = "auto";
  // The exact solver of route (a) (two_step_analytical.hpp); empty: the route is unavailable (the runtime has no
  // computer algebra; `mbgen fit` supplies GiNaC's).
  AnalyticalSolver analytical;
  // Step two's residuals: "normalised" (the thesis's (L(p) - L^) / |L^|, Eq. 3.98) or "covariance" (those whitened by
  // step one's coefficient covariance: the Markov estimate; FRF data only, ARX gives no covariance).
  std::string weighting = "normalised";
  // Time records: step one's black-box model, "armax" (the prediction-error method; unbiased under output noise)
  // or "arx" (least squares; biased under output noise, a high order whitens it); the order criterion ("aic", "bic",
  // "fpe"); the highest ARX order tried; ARMAX orders tried above the model's.
  std::string model = "armax";
  std::string criterion = "aic";
  int max_arx_order = 40;
  int armax_extra_orders = 2;
};

// Throws FitError for data the method cannot use (a record driving several inputs, too short a record, fewer modes
// in the data than the model's order needs, an output whose model transfer function is zero) and bad options.
FitResult fit_two_step(const Model& model, const std::vector<DataSet>& data, const FitOptions& options = {},
                       const TwoStepOptions& two_step = {});

}  // namespace mbgen
