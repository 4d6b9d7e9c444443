#include "matrix_checks.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace mbgen::detail {

void require_shape(const Eigen::MatrixXd& X, Eigen::Index rows, Eigen::Index cols, const char* name,
                   const char* where) {
  if (X.rows() == rows && X.cols() == cols) return;
  std::ostringstream msg;
  msg << where << ": matrix " << name << " is " << X.rows() << "x" << X.cols() << ", expected " << rows << "x"
      << cols;
  throw DynamicsError(msg.str());
}

void require_square(const Eigen::MatrixXd& X, Eigen::Index n, const char* name, const char* where) {
  require_shape(X, n, n, name, where);
}

Eigen::PartialPivLU<Eigen::MatrixXd> factor_mass(const Eigen::MatrixXd& M, const char* where) {
  if (M.rows() != M.cols()) {
    std::ostringstream msg;
    msg << where << ": mass matrix M is " << M.rows() << "x" << M.cols() << ", not square";
    throw DynamicsError(msg.str());
  }
  if (!M.allFinite()) throw DynamicsError(std::string(where) + ": mass matrix M has non-finite entries");
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
  const double threshold = static_cast<double>(M.rows()) * std::numeric_limits<double>::epsilon();
  // Eigen's rcond() estimate returns 1 for an exactly zero pivot, so check the pivots of U as well.
  double rcond = 1.0;
  if (M.size() > 0) {
    const Eigen::VectorXd pivots = lu.matrixLU().diagonal().cwiseAbs();
    rcond = std::min(lu.rcond(), pivots.minCoeff() / pivots.maxCoeff());
  }
  // `!(rcond > threshold)` also catches NaN (all pivots zero).
  if (!(rcond > threshold)) {
    std::ostringstream msg;
    msg << where << ": mass matrix M is singular (reciprocal condition number " << rcond
        << "); every coordinate needs mass or inertia (a massless coordinate makes M singular)";
    throw DynamicsError(msg.str());
  }
  return lu;
}

}  // namespace mbgen::detail
