#include "numerics/balance.hpp"

#include <cmath>

namespace mbgen::numerics {

Eigen::VectorXd balancing_scale(const Eigen::MatrixXd& A) {
  const Eigen::Index n = A.rows();
  Eigen::MatrixXd W = A;
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  for (int sweep = 0; sweep < 100; ++sweep) {
    bool converged = true;
    for (Eigen::Index i = 0; i < n; ++i) {
      double c = W.col(i).norm(), r = W.row(i).norm();
      c = std::sqrt(std::max(c * c - W(i, i) * W(i, i), 0.0));
      r = std::sqrt(std::max(r * r - W(i, i) * W(i, i), 0.0));
      if (c == 0 || r == 0 || !std::isfinite(c) || !std::isfinite(r)) continue;
      const double sum = c + r;
      double f = 1;
      while (c < r / 2) {
        c *= 2;
        r /= 2;
        f *= 2;
      }
      while (c >= 2 * r) {
        c /= 2;
        r *= 2;
        f /= 2;
      }
      if (c + r < 0.95 * sum) {
        converged = false;
        d[i] *= f;
        W.row(i) /= f;
        W.col(i) *= f;
      }
    }
    if (converged) break;
  }
  return d;
}

}  // namespace mbgen::numerics
