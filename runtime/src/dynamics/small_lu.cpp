#include "small_lu.hpp"

#include "pivot_arithmetic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace mbgen::detail {

using cd = std::complex<double>;

void SmallLu::resize(Eigen::Index n) {
  lu_.resize(n, n);
  pivot_.resize(static_cast<std::size_t>(n));
  inverse_.resize(static_cast<std::size_t>(n));
}

double SmallLu::factor() {
  const Eigen::Index n = lu_.rows();
  // The pivots' extremes are kept as |pivot|^2 and their square roots taken once at the end (a root is monotonic
  // and correctly rounded: the same ratio as from the roots of every pivot, without n roots on the critical path).
  double smallest = std::numeric_limits<double>::infinity(), largest = 0;
  bool singular = false;
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Index p = k;
    double best = norm2(lu_(k, k));
    for (Eigen::Index i = k + 1; i < n; ++i)
      if (norm2(lu_(i, k)) > best) best = norm2(lu_(i, k)), p = i;
    pivot_[static_cast<std::size_t>(k)] = p;
    if (p != k) lu_.row(k).swap(lu_.row(p));
    smallest = std::min(smallest, best);
    largest = std::max(largest, best);
    if (best == 0 || !std::isfinite(best)) {
      singular = true;
      inverse_[static_cast<std::size_t>(k)] = 0;
      continue;  // singular: no elimination with this column; factor() reports ratio 0
    }
    const cd inv = reciprocal(lu_(k, k));
    inverse_[static_cast<std::size_t>(k)] = inv;
    for (Eigen::Index i = k + 1; i < n; ++i) lu_(i, k) *= inv;
    for (Eigen::Index j = k + 1; j < n; ++j) {
      const cd u = lu_(k, j);
      if (u == 0.0) continue;
      for (Eigen::Index i = k + 1; i < n; ++i) lu_(i, j) -= lu_(i, k) * u;
    }
  }
  if (n == 0) return 1;
  return singular ? 0 : std::sqrt(smallest) / std::sqrt(largest);
}

void SmallLu::solve(Matrix& x) const {
  const Eigen::Index n = lu_.rows();
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    cd* b = &x(0, c);
    for (Eigen::Index k = 0; k < n; ++k) std::swap(b[k], b[pivot_[static_cast<std::size_t>(k)]]);
    for (Eigen::Index k = 0; k < n; ++k)  // L y = b, unit diagonal, column by column
      for (Eigen::Index i = k + 1; i < n; ++i) b[i] -= lu_(i, k) * b[k];
    for (Eigen::Index k = n - 1; k >= 0; --k) {  // U x = y
      b[k] *= inverse_[static_cast<std::size_t>(k)];
      for (Eigen::Index i = 0; i < k; ++i) b[i] -= lu_(i, k) * b[k];
    }
  }
}

void SmallLu::solve_transposed(Matrix& x) const {
  // A = P^T L U, so A^T = U^T L^T P: U^T z = b, L^T w = z, x = P^T w (the swaps in reverse order). The right-hand
  // sides go through each step together (an FRF's adjoint has one per output), each with the same operations in
  // the same order as alone.
  const Eigen::Index n = lu_.rows(), columns = x.cols(), stride = x.outerStride();
  cd* const x0 = x.data();
  for (Eigen::Index k = 0; k < n; ++k) {  // U^T lower triangular: row k of U^T is column k of U
    const cd* u = &lu_(0, k);
    const cd inverse = inverse_[static_cast<std::size_t>(k)];
    for (Eigen::Index c = 0; c < columns; ++c) {
      cd* b = x0 + c * stride;
      cd s = b[k];
      for (Eigen::Index i = 0; i < k; ++i) s -= u[i] * b[i];
      b[k] = s * inverse;
    }
  }
  for (Eigen::Index k = n - 1; k >= 0; --k) {  // L^T upper triangular, unit diagonal
    const cd* l = &lu_(0, k);
    for (Eigen::Index c = 0; c < columns; ++c) {
      cd* b = x0 + c * stride;
      cd s = b[k];
      for (Eigen::Index i = k + 1; i < n; ++i) s -= l[i] * b[i];
      b[k] = s;
    }
  }
  for (Eigen::Index c = 0; c < columns; ++c) {
    cd* b = x0 + c * stride;
    for (Eigen::Index k = n - 1; k >= 0; --k) std::swap(b[k], b[pivot_[static_cast<std::size_t>(k)]]);
  }
}

}  // namespace mbgen::detail
