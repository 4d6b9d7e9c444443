#include "mbgen/dynamics/model_modes.hpp"

#include "matrix_checks.hpp"
#include "mbgen/dynamics/dynamics_error.hpp"
#include "numerics/constants.hpp"
#include "numerics/state_eigen.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace mbgen {
namespace {

using numerics::kTwoPi;

Mode make_mode(std::complex<double> lambda, const Eigen::VectorXcd& state_vector, Eigen::Index n) {
  Mode mode;
  mode.eigenvalue = lambda;
  mode.f_hz = numerics::pole_frequency_hz(lambda);
  mode.zeta = numerics::pole_damping_ratio(lambda);
  mode.shape = state_vector.head(n);
  // Scale so that the largest entry is exactly 1: removes the solver's arbitrary complex factor.
  Eigen::Index largest = 0;
  if (n > 0) mode.shape.cwiseAbs().maxCoeff(&largest);
  if (n > 0 && std::abs(mode.shape[largest]) > 0) {
    const std::complex<double> scale = mode.shape[largest];
    mode.shape /= scale;
    mode.shape[largest] = 1.0;
  }
  return mode;
}

}  // namespace

std::vector<Mode> modal_analysis(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K) {
  const char* where = "modal_analysis";
  const Eigen::Index n = M.rows();
  const auto lu = detail::factor_mass(M, where);
  detail::require_square(C, n, "C", where);
  detail::require_square(K, n, "K", where);

  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -lu.solve(K);
  A.bottomRightCorner(n, n) = -lu.solve(C);
  if (!A.allFinite())  // 1e300 next to 1e-300: no double holds M^-1 K, and the iteration below cannot converge
    throw DynamicsError("modal_analysis: M^-1 K or M^-1 C overflows a double at these parameter values (masses and "
                        "stiffnesses or dampings too far apart)");

  const auto eig = numerics::state_eigen(A, numerics::EigenVectors::right);
  if (!eig) throw DynamicsError("modal_analysis: the eigenvalue iteration did not converge");
  std::vector<Mode> modes;
  for (const Eigen::Index e : numerics::listed_modes(eig->lambda))
    modes.push_back(make_mode(eig->lambda[e], eig->right.col(e), n));
  return modes;
}

Eigen::VectorXd undamped_natural_frequencies_hz(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K) {
  const char* where = "undamped_natural_frequencies_hz";
  detail::factor_mass(M, where);
  detail::require_square(K, M.rows(), "K", where);
  const Eigen::MatrixXd Ms = 0.5 * (M + M.transpose());
  const Eigen::MatrixXd Ks = 0.5 * (K + K.transpose());
  if (Eigen::LLT<Eigen::MatrixXd>(Ms).info() != Eigen::Success)
    throw DynamicsError(std::string(where) + ": mass matrix M is not positive definite");
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(Ks, Ms, Eigen::EigenvaluesOnly | Eigen::Ax_lBx);
  if (solver.info() != Eigen::Success) throw DynamicsError(std::string(where) + ": eigen solver failed");
  Eigen::VectorXd f = solver.eigenvalues();  // ascending
  for (Eigen::Index i = 0; i < f.size(); ++i) f[i] = std::sqrt(std::max(f[i], 0.0)) / kTwoPi;
  return f;
}

Eigen::MatrixXd modal_assurance_criterion(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& b) {
  if (a.rows() != b.rows())
    throw DynamicsError("modal_assurance_criterion: shape sets have different lengths (" +
                        std::to_string(a.rows()) + " and " + std::to_string(b.rows()) + ")");
  Eigen::MatrixXd mac(a.cols(), b.cols());
  for (Eigen::Index i = 0; i < a.cols(); ++i) {
    const double aa = a.col(i).squaredNorm();
    for (Eigen::Index j = 0; j < b.cols(); ++j) {
      const double bb = b.col(j).squaredNorm();
      const double denominator = aa * bb;
      mac(i, j) = denominator > 0 ? std::norm(a.col(i).dot(b.col(j))) / denominator : 0.0;
    }
  }
  return mac;
}

namespace {
Eigen::MatrixXcd shape_matrix(const std::vector<Mode>& modes) {
  const Eigen::Index rows = modes.empty() ? 0 : modes.front().shape.size();
  Eigen::MatrixXcd shapes(rows, static_cast<Eigen::Index>(modes.size()));
  for (std::size_t j = 0; j < modes.size(); ++j) {
    if (modes[j].shape.size() != rows) throw DynamicsError("modal_assurance_criterion: modes of different lengths");
    shapes.col(static_cast<Eigen::Index>(j)) = modes[j].shape;
  }
  return shapes;
}
}  // namespace

Eigen::MatrixXd modal_assurance_criterion(const std::vector<Mode>& a, const std::vector<Mode>& b) {
  return modal_assurance_criterion(shape_matrix(a), shape_matrix(b));
}

}  // namespace mbgen
