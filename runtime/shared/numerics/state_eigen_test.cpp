#include "numerics/state_eigen.hpp"

#include <catch2/catch.hpp>

#include <Eigen/LU>

#include <cmath>

using namespace mbgen::numerics;
using Complex = std::complex<double>;

namespace {

// A two-mass chain, ground - k1 - m1 - k2 - m2, with Rayleigh damping C = a M + b K: its eigenvalues follow from
// the undamped modes in closed form, independently of any eigensolver.
struct Chain {
  double m1, m2, k1, k2, a, b;
  Eigen::MatrixXd state_matrix() const {
    Eigen::Matrix2d M, K;
    M << m1, 0, 0, m2;
    K << k1 + k2, -k2, -k2, k2;
    const Eigen::Matrix2d C = a * M + b * K;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
    A.topRightCorner(2, 2).setIdentity();
    A.bottomLeftCorner(2, 2) = -M.inverse() * K;
    A.bottomRightCorner(2, 2) = -M.inverse() * C;
    return A;
  }
  // w^2 solves m1 m2 w^4 - (m1 k2 + m2 (k1 + k2)) w^2 + k1 k2 = 0; each mode's zeta = (a / w + b w) / 2.
  std::vector<Complex> poles() const {
    const double p = m1 * k2 + m2 * (k1 + k2), disc = std::sqrt(p * p - 4 * m1 * m2 * k1 * k2);
    const double w2_low = 2 * k1 * k2 / (p + disc), w2_high = (p + disc) / (2 * m1 * m2);  // no cancellation
    std::vector<Complex> out;
    for (const double w2 : {w2_low, w2_high}) {
      const double w = std::sqrt(w2), zeta = (a / w + b * w) / 2;
      out.emplace_back(-zeta * w, w * std::sqrt(1 - zeta * zeta));
    }
    return out;
  }
};

}  // namespace

TEST_CASE("state eigenproblem of a stiff chain: eigenvalues, both eigenvector sets, the listed modes", "[numerics]") {
  // 1e-3 kg on 1e9 N/m next to 10 kg on 1e4 N/m: M^-1 K spans 1e12 next to the identity block.
  const Chain chain{10, 1e-3, 1e4, 1e9, 0.5, 2e-8};
  const Eigen::MatrixXd A = chain.state_matrix();
  const auto eig = state_eigen(A, EigenVectors::right_and_left);
  REQUIRE(eig);
  const std::vector<Eigen::Index> modes = listed_modes(eig->lambda);
  REQUIRE(modes.size() == 2);
  const std::vector<Complex> expected = chain.poles();
  // A backward-stable solver errs by about eps times the norm of the matrix it iterates on: the balanced A's is
  // about |lambda_max| = 1e6 (error ~1e-10), the unbalanced A's is 1e12 (error ~1e-4), more than this bound.
  const double bound = 1e-13 * std::abs(expected[1]);
  for (std::size_t k = 0; k < 2; ++k) CHECK(std::abs(eig->lambda[modes[k]] - expected[k]) <= bound);
  CHECK(std::abs(eig->lambda[modes[1]] - expected[1]) <= 1e-14 * std::abs(expected[1]));
  const Eigen::MatrixXcd Ac = A.cast<Complex>();
  const Eigen::MatrixXcd residual = Ac * eig->right - eig->right * eig->lambda.asDiagonal();
  CHECK(residual.norm() <= 1e-12 * Ac.norm() * eig->right.norm());
  CHECK((eig->left * eig->right - Eigen::MatrixXcd::Identity(4, 4)).norm() <= 1e-10);

  // The velocity-block scaling makes the two blocks comparable too, and meets the same bound.
  const auto blocks = state_eigen(A, EigenVectors::right_and_left, Scaling::velocity_block);
  REQUIRE(blocks);
  const std::vector<Eigen::Index> block_modes = listed_modes(blocks->lambda);
  REQUIRE(block_modes.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) CHECK(std::abs(blocks->lambda[block_modes[k]] - expected[k]) <= bound);
  CHECK((blocks->left * blocks->right - Eigen::MatrixXcd::Identity(4, 4)).norm() <= 1e-10);
  CHECK((Ac * blocks->right - blocks->right * blocks->lambda.asDiagonal()).norm() <=
        1e-12 * Ac.norm() * blocks->right.norm());

  const auto values_only = state_eigen(A, EigenVectors::none);
  REQUIRE(values_only);
  CHECK(values_only->right.size() == 0);
  CHECK((values_only->lambda - eig->lambda).norm() == 0.0);
}

TEST_CASE("listed modes: one per conjugate pair and every real eigenvalue, by frequency then damping", "[numerics]") {
  Eigen::VectorXcd lambda(6);
  lambda << Complex(-1, 100), Complex(-1, -100), Complex(-50, 0), Complex(-2, 30), Complex(-2, -30), Complex(-30, 0);
  const std::vector<Eigen::Index> modes = listed_modes(lambda);
  // |lambda|: 30 (real), 30.07 (pair), 50 (real), 100.005 (pair).
  CHECK(modes == std::vector<Eigen::Index>{5, 3, 2, 0});
}
