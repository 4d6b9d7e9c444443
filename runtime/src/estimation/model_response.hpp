// Model responses with analytic parameter Jacobians, for the estimators. Internal header.
//
// This is an adapter: the dynamics library's frf.hpp / simulate.hpp were not available when the estimators were
// written, so the two responses the output-error fits need are computed here directly from mbgen::Model.
//
//  FRF:  P(jw) = K + jw C - w^2 M,  H = c(jw) P^-1 B,  c(jw) = Cd + jw Cv - w^2 Ca,
//        dH/dp = dc X + Y (dB - dP X)   with X = P^-1 B and Y = c P^-1 (one LU per frequency).
//  Time: x = [q; q'],  x' = A x + Bc u,  y = Cx x + D u  (q'' eliminated through M^-1), discretised exactly
//        for a zero- or first-order-hold input by the matrix exponential; the output sensitivities dy/dp follow
//        from the same discretisation of the system augmented with s = dx/dp:  s' = A s + dA x + dBc u.
#pragma once

#include "mbgen/model.hpp"
#include "mbgen/data_settings.hpp"

#include <Eigen/Core>

#include <complex>
#include <vector>

namespace mbgen::estimation {

// Dense derivatives of all seven matrices with respect to each parameter in `params` (model indices).
struct DenseDerivative {
  Eigen::MatrixXd M, C, K, B, Cd, Cv, Ca;
  bool any = false;  // some entry is non-zero
};
std::vector<DenseDerivative> dense_derivatives(const ModelMatrices& m, const ModelDerivatives& d,
                                               const std::vector<int>& params);

// One FRF channel to compute: output and input indices.
struct ChannelIndex {
  int output = 0, input = 0;
};

// H[c](k) for channel c at frequency f_hz(k); jacobian[c] is (frequencies x params) when requested.
struct FrfResponse {
  std::vector<Eigen::VectorXcd> values;
  std::vector<Eigen::MatrixXcd> jacobian;
};
// `derivatives` (sparse, as the model gives them) are taken for the parameters `params` (model indices);
// parameters listed in `inactive` get zero columns (a data set's `# set` values).
FrfResponse frf_response(const ModelMatrices& m, const ModelDerivatives* derivatives, const std::vector<int>& params,
                         const std::vector<int>& inactive, const Eigen::VectorXd& f_hz,
                         const std::vector<ChannelIndex>& channels);

// y[o] (samples) for output index outputs[o]; sensitivity[o] is (samples x params) when requested.
// Inputs: u is (samples x model inputs). The state starts at rest.
struct TimeResponse {
  std::vector<Eigen::VectorXd> values;
  std::vector<Eigen::MatrixXd> sensitivity;
};
TimeResponse time_response(const ModelMatrices& m, const std::vector<DenseDerivative>* derivatives,
                           const Eigen::MatrixXd& u, double dt, HoldMode hold, const std::vector<int>& outputs);

}  // namespace mbgen::estimation
