// LU factorisation with partial pivoting of a small dense complex matrix, in place, in a buffer that is reused
// from one factorisation to the next (the dynamic stiffness P(jw) at every frequency of an FRF). Internal header.
//
// Why not Eigen::PartialPivLU: for the n = 2..20 matrices of lumped models its blocked, general code and the
// fresh allocations per frequency cost more than the arithmetic; here a pivot row's reciprocal is formed once
// (no complex division per entry) and the pivot is chosen by |re|^2 + |im|^2 (no hypot).
#pragma once

#include <Eigen/Core>

#include <complex>
#include <vector>

namespace mbgen::detail {

class SmallLu {
 public:
  using Matrix = Eigen::MatrixXcd;

  // The matrix to factor: fill it, then call factor(). Resized by resize().
  void resize(Eigen::Index n);
  Matrix& matrix() { return lu_; }

  // Factors the matrix in place: row-permuted A = L U, L unit lower triangular. Returns the smallest over the
  // largest |pivot| (0 for an exactly singular matrix or a non-finite pivot; 1 for an empty one), the caller's singularity test.
  double factor();

  // x <- A^-1 x and x <- A^-T x (plain transpose, not the conjugate) for a matrix of right-hand sides.
  void solve(Matrix& x) const;
  void solve_transposed(Matrix& x) const;

 private:
  Matrix lu_;
  std::vector<Eigen::Index> pivot_;            // row swapped with row k at step k
  std::vector<std::complex<double>> inverse_;  // 1 / U(k, k)
};

}  // namespace mbgen::detail
