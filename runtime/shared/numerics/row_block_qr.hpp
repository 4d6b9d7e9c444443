// The triangular factor of a tall least-squares problem, J = Q R, with Q^T r, without Q. Internal header.
//
// Levenberg-Marquardt needs only R and the first columns of Q^T r. An FRF fit's J has tens of thousands of rows
// and a handful of columns (frame3: 73 728 x 9, 5.3 MB): Eigen's HouseholderQR copies it and, with fewer columns
// than its block size, applies each reflection to the whole remaining matrix, one pass over memory per column
// pair, and then Q^T r is one more. Here [J r] is reduced a few dozen rows at a time (a tall-skinny QR): the rows
// of a block are annihilated against the (k+1) x (k+1) triangle kept so far, so each row is read once and every
// reflection works in cache. The same backward-stable Householder reflections, applied in another order: R and
// Q^T r agree with Eigen's to rounding (up to the signs of R's rows, which Q^T r shares).
#pragma once

#include <Eigen/Core>

namespace mbgen::estimation {

// R (k x k, upper triangular; rows beyond J's row count are zero) and qtr (k: the first k entries of Q^T r) of
// J (m x k) and r (m).
void row_block_qr(const Eigen::MatrixXd& J, const Eigen::VectorXd& r, Eigen::MatrixXd& R, Eigen::VectorXd& qtr);

}  // namespace mbgen::estimation
