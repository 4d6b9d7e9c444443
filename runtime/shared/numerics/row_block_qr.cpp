#include "numerics/row_block_qr.hpp"

#include <algorithm>
#include <cmath>

namespace mbgen::estimation {

void row_block_qr(const Eigen::MatrixXd& J, const Eigen::VectorXd& r, Eigen::MatrixXd& R, Eigen::VectorXd& qtr) {
  const Eigen::Index m = J.rows(), k = J.cols(), K = k + 1;
  // Rows per block: each reflection's dot products and updates run over this many rows. At 64 rows (an L1-sized
  // block) their fixed cost per column pair dominated: on 5 to 50 columns 512 rows took 0.7-0.8 times as long,
  // with the block in L2 (512 x (k + 1) doubles).
  constexpr Eigen::Index block = 512;
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(K, K);  // the triangle of [J r] so far
  Eigen::MatrixXd B(std::min(block, std::max<Eigen::Index>(m, 1)), K);
  for (Eigen::Index first = 0; first < m; first += block) {
    const Eigen::Index n = std::min(block, m - first);
    for (Eigen::Index c = 0; c < k; ++c) std::copy_n(J.col(c).data() + first, n, B.col(c).data());
    std::copy_n(r.data() + first, n, B.col(k).data());
    // Column j: the reflection H = I - tau v v^T taking [T(j, j); B(:, j)] to [beta; 0], with v = [1; B(:, j) / v0],
    // applied to the columns after j (Eigen's makeHouseholder convention: beta has the opposite sign of T(j, j)).
    for (Eigen::Index j = 0; j < K; ++j) {
      const double tail = B.col(j).head(n).squaredNorm();
      if (tail == 0) continue;  // nothing below the diagonal: H = I
      const double alpha = T(j, j);
      const double norm = std::sqrt(alpha * alpha + tail);
      const double beta = alpha >= 0 ? -norm : norm;
      const double tau = (beta - alpha) / beta;
      B.col(j).head(n) *= 1 / (alpha - beta);
      T(j, j) = beta;
      for (Eigen::Index c = j + 1; c < K; ++c) {
        const double s = tau * (T(j, c) + B.col(j).head(n).dot(B.col(c).head(n)));
        T(j, c) -= s;
        B.col(c).head(n) -= s * B.col(j).head(n);
      }
    }
  }
  R = T.topLeftCorner(k, k);
  qtr = T.col(k).head(k);
}

}  // namespace mbgen::estimation
