// The row-block QR against Eigen's HouseholderQR (an independent implementation): the same R up to the signs of
// its rows, the same Q^T r with those signs, on tall, short and rank-deficient matrices.
#include "numerics/row_block_qr.hpp"

#include <Eigen/QR>

#include <catch2/catch.hpp>

#include <random>

using mbgen::estimation::row_block_qr;

namespace {

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd A(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) A(i, j) = normal(rng);
  return A;
}

// Compares with Eigen's factorisation: |R| row by row (a row's sign is the reflection's choice) and Q^T r with the
// same signs; both relative to the matrix's size.
void check_against_eigen(const Eigen::MatrixXd& J, const Eigen::VectorXd& r) {
  const Eigen::Index k = J.cols(), kk = std::min(J.rows(), k);
  Eigen::MatrixXd R;
  Eigen::VectorXd qtr;
  row_block_qr(J, r, R, qtr);
  REQUIRE(R.rows() == k);
  REQUIRE(R.cols() == k);
  REQUIRE(qtr.size() == k);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(J);
  Eigen::MatrixXd R_ref = Eigen::MatrixXd::Zero(k, k);
  R_ref.topRows(kk) = qr.matrixQR().topRows(kk).triangularView<Eigen::Upper>();
  Eigen::VectorXd qtr_ref = Eigen::VectorXd::Zero(k);
  qtr_ref.head(kk) = (qr.householderQ().transpose() * r).head(kk);
  const double scale = J.norm() + r.norm();
  for (Eigen::Index i = 0; i < k; ++i) {
    // The sign of row i: that of its largest entry in Eigen's factor.
    Eigen::Index at = 0;
    R_ref.row(i).cwiseAbs().maxCoeff(&at);
    const double sign = (R(i, at) >= 0) == (R_ref(i, at) >= 0) ? 1.0 : -1.0;
    INFO("rows " << J.rows() << ", row " << i);
    CHECK((sign * R.row(i) - R_ref.row(i)).norm() <= 1e-12 * scale);
    CHECK(std::abs(sign * qtr[i] - qtr_ref[i]) <= 1e-12 * scale);
    for (Eigen::Index j = 0; j < i; ++j) CHECK(R(i, j) == 0);
  }
}

}  // namespace

TEST_CASE("row-block QR: R and Q^T r of tall and short matrices like Eigen's HouseholderQR", "[estimation][qr]") {
  std::mt19937 rng(17);
  for (Eigen::Index rows : {1, 3, 9, 63, 64, 65, 200, 511, 512, 513, 1500, 4097})
    for (Eigen::Index cols : {1, 4, 9}) {
      const Eigen::MatrixXd J = random_matrix(rows, cols, rng);
      check_against_eigen(J, random_matrix(rows, 1, rng).col(0));
    }
}

TEST_CASE("row-block QR: a zero column and a repeated column", "[estimation][qr]") {
  std::mt19937 rng(23);
  Eigen::MatrixXd J = random_matrix(300, 5, rng);
  J.col(1).setZero();
  J.col(3) = 2 * J.col(0);  // rank 3
  const Eigen::VectorXd r = random_matrix(300, 1, rng).col(0);
  Eigen::MatrixXd R;
  Eigen::VectorXd qtr;
  row_block_qr(J, r, R, qtr);
  // J^T J = R^T R and J^T r = R^T qtr whatever the rank.
  CHECK((R.transpose() * R - J.transpose() * J).norm() <= 1e-12 * J.squaredNorm());
  CHECK((R.transpose() * qtr - J.transpose() * r).norm() <= 1e-12 * J.norm() * r.norm());
  CHECK(R.col(1).norm() == 0);
}
