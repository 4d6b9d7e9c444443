#include "estimator.hpp"

#include "fit_setup.hpp"

#include <cmath>
#include <stdexcept>

namespace mbgen::estimation {

Eigen::VectorXd Estimator::full_values(const std::vector<int>& free, const Eigen::VectorXd& theta) const {
  return physical_values(prior_, free, transforms_, theta);
}

Eigen::VectorXd Estimator::full_values(const std::vector<int>& free, const Eigen::VectorXd& theta,
                                       const Eigen::VectorXd& held_at) const {
  return physical_values(held_at, free, transforms_, theta);
}

Eigen::VectorXd Estimator::internal(const std::vector<int>& free, const Eigen::VectorXd& full) const {
  return internal_values(free, transforms_, full);
}

ResidualFunction Estimator::function(const std::vector<int>& free, ResidualKind kind) const {
  return function(free, kind, prior_);
}

ResidualFunction Estimator::function(const std::vector<int>& free, ResidualKind kind,
                                     const Eigen::VectorXd& held_at) const {
  return [this, free, kind, held_at](const Eigen::VectorXd& theta, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    const Eigen::VectorXd full = full_values(free, theta, held_at);
    // The chain rule to theta, applied as the Jacobian is written.
    Eigen::VectorXd derivative(static_cast<Eigen::Index>(free.size()));
    for (std::size_t j = 0; j < free.size(); ++j)
      derivative[static_cast<Eigen::Index>(j)] =
          transforms_[static_cast<std::size_t>(free[j])].derivative(theta[static_cast<Eigen::Index>(j)]);
    try {
      problem_.evaluate(full, free, kind, r, J, &derivative);
    } catch (const std::runtime_error&) {
      // e.g. a singular mass matrix far from the prior (DynamicsError): a failed trial step. Only runtime errors,
      // the kind mbgen throws for what the input makes fail: a std::logic_error (out_of_range from .at() too) is a
      // bug, and was taken for a failed step; it goes on to the command's internal-error status (docs/cli.md).
      return false;
    }
    return true;
  };
}

Eigen::MatrixXd Estimator::scaled_jacobian(const std::vector<int>& free, const Eigen::VectorXd& full,
                                           Eigen::VectorXd* scale_out, Eigen::VectorXd* r_out) const {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  problem_.evaluate(full, free, ResidualKind::Weighted, r, &J);
  Eigen::VectorXd scale(static_cast<Eigen::Index>(free.size()));
  for (std::size_t j = 0; j < free.size(); ++j) {
    const double v = std::abs(full[free[j]]);
    scale[static_cast<Eigen::Index>(j)] = v > 0 ? v : transforms_[static_cast<std::size_t>(free[j])].scale;
  }
  if (scale_out) *scale_out = scale;
  if (r_out) *r_out = r;
  return J * scale.asDiagonal();
}

}  // namespace mbgen::estimation
