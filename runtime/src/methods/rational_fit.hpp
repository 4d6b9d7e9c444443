// Step one of the two-step method from FRFs: a continuous-time rational model with a common monic denominator of
// order q for the channels of one input, H_c(s) = N_c(s) / D(s), deg N_c = the model's numerator degree of that
// channel. Internal header.
//
// Sanathanan-Koerner iterations give the start: the linearised error (D H - N) / D_prev, weighted by the
// measurement's standard deviation, is linear in the coefficients (D_prev = 1 first: Levy's fit), solved by
// column-scaled QR; unstable roots of D are reflected into the left half-plane between iterations. Then
// Levenberg-Marquardt on the true weighted error (N / D - H) / sigma: the maximum-likelihood coefficients for
// Gaussian noise, and their covariance s^2 (J^T J)^-1 with s^2 = RSS / (n - p). Everything runs in the scaled
// variable s / omega0 (omega0 about the band's modes), where the coefficients are of similar size; they are
// unscaled at the end.
#pragma once

#include "identified_tf.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mbgen::methods {

struct RationalChannel {
  std::string output;
  Eigen::VectorXcd H;      // measured, per line
  Eigen::VectorXd sigma;   // standard deviation of the real (and of the imaginary) part, per line
  int numerator_degree = 0;
};

struct RationalFitReport {
  int sk_iterations = 0;
  int lm_iterations = 0;
  bool converged = false;
  int reflected_poles = 0;  // unstable roots reflected during the SK iterations
  double cost = 0;          // weighted RSS at the end
  long residual_count = 0;
  double nrmse = 0;         // sqrt(RSS / sum of squared weighted measurements)
};

// omega: rad/s of the lines (> 0); omega0 > 0 the scale. Throws std::invalid_argument when the lines cannot
// determine the coefficients (fewer real equations than unknowns).
IdentifiedTf fit_rational_frf(const Eigen::VectorXd& omega, const std::vector<RationalChannel>& channels,
                              const std::string& input, int order, double omega0, RationalFitReport* report = nullptr);

}  // namespace mbgen::methods
