// Indicators of a mode shape's complexity: MPC (Pappa, Elliott, Schenk 1993) and MPD.
#include "mbgen/modal_identification/modal_identification.hpp"
#include "numerics/constants.hpp"

#include <Eigen/SVD>

#include <cmath>

namespace mbgen {

namespace {

// Singular values and right singular vectors of [Re psi, Im psi]: the principal axes of the shape's
// components in the complex plane.
Eigen::JacobiSVD<Eigen::MatrixXd> principal_axes(const Eigen::VectorXcd& shape) {
  Eigen::MatrixXd points(shape.size(), 2);
  points.col(0) = shape.real();
  points.col(1) = shape.imag();
  return Eigen::JacobiSVD<Eigen::MatrixXd>(points, Eigen::ComputeFullV);
}

}  // namespace

double modal_phase_collinearity(const Eigen::VectorXcd& shape) {
  if (shape.size() == 0 || shape.squaredNorm() <= 0) return 0;
  const Eigen::VectorXd s = principal_axes(shape).singularValues();
  const double l1 = s[0] * s[0], l2 = s.size() > 1 ? s[1] * s[1] : 0.0;
  return std::pow((l1 - l2) / (l1 + l2), 2);
}

double mean_phase_deviation_deg(const Eigen::VectorXcd& shape) {
  const double total = shape.cwiseAbs().sum();
  if (shape.size() == 0 || total <= 0) return 0;
  const Eigen::Vector2d axis = principal_axes(shape).matrixV().col(0);
  const std::complex<double> direction(axis[0], axis[1]);
  double sum = 0;
  for (Eigen::Index j = 0; j < shape.size(); ++j) {
    const double magnitude = std::abs(shape[j]);
    if (magnitude <= 0) continue;
    // The angle between the component and the line through the origin, folded to [0, 90] degrees.
    const double cosine = std::min(1.0, std::abs((shape[j] * std::conj(direction)).real()) / magnitude);
    sum += magnitude * std::acos(cosine);
  }
  return numerics::degrees(sum / total);
}

}  // namespace mbgen
