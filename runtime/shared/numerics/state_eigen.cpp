#include "numerics/state_eigen.hpp"

#include "numerics/balance.hpp"
#include "numerics/constants.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace mbgen::numerics {

namespace {

Eigen::VectorXd velocity_block_scale(const Eigen::MatrixXd& A) {
  const Eigen::Index n = A.rows() / 2;
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(2 * n);
  if (n > 0) scale.tail(n).setConstant(std::sqrt(std::max(1.0, A.bottomLeftCorner(n, n).cwiseAbs().maxCoeff())));
  return scale;
}

}  // namespace

std::optional<StateEigen> state_eigen(const Eigen::MatrixXd& A, EigenVectors vectors, Scaling scaling) {
  const Eigen::VectorXd scale = scaling == Scaling::balance ? balancing_scale(A) : velocity_block_scale(A);
  const Eigen::MatrixXd A_balanced = scale.cwiseInverse().asDiagonal() * A * scale.asDiagonal();
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(A_balanced, vectors != EigenVectors::none);
  if (solver.info() != Eigen::Success) return std::nullopt;
  StateEigen out;
  out.lambda = solver.eigenvalues();
  if (vectors == EigenVectors::none) return out;
  const Eigen::MatrixXcd V = solver.eigenvectors();
  out.right = scale.cast<std::complex<double>>().asDiagonal() * V;
  if (vectors == EigenVectors::right_and_left)
    out.left = V.partialPivLu().inverse() * scale.cwiseInverse().cast<std::complex<double>>().asDiagonal();
  return out;
}

std::vector<Eigen::Index> listed_modes(const Eigen::VectorXcd& lambda) {
  std::vector<Eigen::Index> modes;
  // Real eigenvalues have an imaginary part of exactly 0 (state_eigen), so its sign selects one member of each
  // pair without a tolerance.
  for (Eigen::Index e = 0; e < lambda.size(); ++e)
    if (lambda[e].imag() >= 0) modes.push_back(e);
  std::stable_sort(modes.begin(), modes.end(), [&](Eigen::Index a, Eigen::Index b) {
    const double fa = pole_frequency_hz(lambda[a]), fb = pole_frequency_hz(lambda[b]);
    return fa != fb ? fa < fb : pole_damping_ratio(lambda[a]) < pole_damping_ratio(lambda[b]);
  });
  return modes;
}

}  // namespace mbgen::numerics
