// The state-space form of M q'' + C q' + K q = B u, y = Cd q + Cv q' + Ca q'' for generated code, over any Scalar
// (x = [q; q'], the same formulas as mbgen/dynamics/state_space.hpp's double version):
//
//   A = [[0, I], [-M^-1 K, -M^-1 C]],  B = [0; M^-1 B],  C = [Cd - Ca M^-1 K, Cv - Ca M^-1 C],  D = Ca M^-1 B.
//
// Compiled once in the runtime library for double and long double (src/dynamics/state_space_form.cpp): the
// generated state_space() calls it, so that Eigen's LU is not instantiated again in every generated translation
// unit (and on fixed-size matrices, which Eigen cannot hold beyond ~45 coordinates in long double). Other Scalar
// types (mpfr::mpreal) instantiate it from this header.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

#include "mbgen/transfer_function.hpp"  // DenseMatrix

namespace mbgen {

template <typename Scalar>
void state_space_form(const DenseMatrix<Scalar>& M, const DenseMatrix<Scalar>& C, const DenseMatrix<Scalar>& K,
                      const DenseMatrix<Scalar>& B, const DenseMatrix<Scalar>& Cd, const DenseMatrix<Scalar>& Cv,
                      const DenseMatrix<Scalar>& Ca, DenseMatrix<Scalar>& A_out, DenseMatrix<Scalar>& B_out,
                      DenseMatrix<Scalar>& C_out, DenseMatrix<Scalar>& D_out) {
  const Eigen::Index n = M.rows();
  const Eigen::PartialPivLU<DenseMatrix<Scalar>> lu(M);
  const DenseMatrix<Scalar> MinvK = lu.solve(K), MinvC = lu.solve(C), MinvB = lu.solve(B);
  A_out.setZero(2 * n, 2 * n);
  A_out.topRightCorner(n, n).setIdentity();
  A_out.bottomLeftCorner(n, n) = -MinvK;
  A_out.bottomRightCorner(n, n) = -MinvC;
  B_out.setZero(2 * n, B.cols());
  B_out.bottomRows(n) = MinvB;
  C_out.resize(Cd.rows(), 2 * n);
  C_out.leftCols(n) = Cd - Ca * MinvK;
  C_out.rightCols(n) = Cv - Ca * MinvC;
  D_out = Ca * MinvB;
}

#define MBGEN_STATE_SPACE_FORM_INSTANTIATION(EXTERN, Scalar)                                                     \
  EXTERN template void state_space_form<Scalar>(                                                                \
      const DenseMatrix<Scalar>&, const DenseMatrix<Scalar>&, const DenseMatrix<Scalar>&,                       \
      const DenseMatrix<Scalar>&, const DenseMatrix<Scalar>&, const DenseMatrix<Scalar>&,                       \
      const DenseMatrix<Scalar>&, DenseMatrix<Scalar>&, DenseMatrix<Scalar>&, DenseMatrix<Scalar>&,             \
      DenseMatrix<Scalar>&);
#ifndef MBGEN_STATE_SPACE_FORM_INSTANTIATE
MBGEN_STATE_SPACE_FORM_INSTANTIATION(extern, double)
MBGEN_STATE_SPACE_FORM_INSTANTIATION(extern, long double)
#endif

}  // namespace mbgen
