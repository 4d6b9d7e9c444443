// The uncertainty of a fitted model's FRF from its parameters' covariance, by the delta method (docs/estimation.md,
// "Confidence bands on the Bode overlays"): for one channel H(f; p) with parameter Jacobian g = dH/dp,
//
//   d|H|/dp     = Re(conj(H) g) / |H|          std |H|   = sqrt(a^T Cov a),  a = d|H|/dp
//   d arg H/dp  = Im(conj(H) g) / |H|^2        std phase = sqrt(b^T Cov b),  b = d arg H/dp (in degrees)
//
// Cov is the covariance of the estimated parameters (FitResult::covariance); the others are held at their values.
#pragma once

#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace mbgen {

struct FrfBand {
  Eigen::VectorXcd H;              // at the estimate, per line
  Eigen::VectorXd magnitude_std;   // std of |H|, per line
  Eigen::VectorXd phase_std_deg;   // std of the phase in degrees, per line
};

// The band of the FRF from model input `input` to model output `output` (indices in ModelInfo) at `values` (all model
// parameters). `estimated`: the model indices of the covariance's rows, in its order; a parameter whose index is in
// `held` (a data set's `# set` value) contributes nothing. Throws DynamicsError where the FRF cannot be evaluated.
FrfBand frf_band(const Model& model, const Eigen::VectorXd& values, const std::vector<int>& estimated,
                 const Eigen::MatrixXd& covariance, const std::vector<double>& f_hz, int output, int input,
                 const std::vector<int>& held = {});

// The bands of several channels (output, input) at once, from one evaluation of the FRF's Jacobian.
std::vector<FrfBand> frf_bands(const Model& model, const Eigen::VectorXd& values, const std::vector<int>& estimated,
                               const Eigen::MatrixXd& covariance, const std::vector<double>& f_hz,
                               const std::vector<std::pair<int, int>>& channels, const std::vector<int>& held = {});

}  // namespace mbgen
