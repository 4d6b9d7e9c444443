// The output-error problem over a chosen set of free parameters, in the optimiser's internal coordinates
// (parameterization.hpp): the residual function Levenberg-Marquardt minimises, and the Jacobian in physical units
// that identifiability and uncertainty are judged by. Internal header (fit.cpp).
#pragma once

#include "numerics/levenberg_marquardt.hpp"
#include "output_error.hpp"

#include "mbgen/estimation/parameterization.hpp"

#include <Eigen/Core>

#include <vector>

namespace mbgen::estimation {

class Estimator {
 public:
  // `problem` must outlive the Estimator. Parameters not free stay at `prior`.
  Estimator(const OutputErrorProblem& problem, const Eigen::VectorXd& prior, std::vector<ParameterTransform> transforms)
      : problem_(problem), prior_(prior), transforms_(std::move(transforms)) {}

  // The full parameter vector with the free ones at internal coordinates theta (the others at `held_at`, by
  // default the prior), and back.
  Eigen::VectorXd full_values(const std::vector<int>& free, const Eigen::VectorXd& theta) const;
  Eigen::VectorXd full_values(const std::vector<int>& free, const Eigen::VectorXd& theta,
                              const Eigen::VectorXd& held_at) const;
  Eigen::VectorXd internal(const std::vector<int>& free, const Eigen::VectorXd& full) const;

  // r(theta) and its Jacobian with respect to theta; false where the model cannot be evaluated (a failed trial step).
  ResidualFunction function(const std::vector<int>& free, ResidualKind kind) const;
  // The same with the parameters not free at `held_at` (all model parameters) instead of the prior.
  ResidualFunction function(const std::vector<int>& free, ResidualKind kind, const Eigen::VectorXd& held_at) const;

  // Jacobian of the weighted residuals in physical units with columns multiplied by the parameters' magnitudes
  // (relative sensitivities; a parameter at zero by its transform's scale). `scale_out` and `r_out` receive that
  // scale and the residuals when non-null.
  Eigen::MatrixXd scaled_jacobian(const std::vector<int>& free, const Eigen::VectorXd& full,
                                  Eigen::VectorXd* scale_out, Eigen::VectorXd* r_out = nullptr) const;

 private:
  const OutputErrorProblem& problem_;
  Eigen::VectorXd prior_;
  std::vector<ParameterTransform> transforms_;
};

}  // namespace mbgen::estimation
