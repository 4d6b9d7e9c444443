#include "band_lu.hpp"

#include "pivot_arithmetic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace mbgen::detail {

using cd = std::complex<double>;

Bandwidth bandwidth_of(const std::vector<const Eigen::MatrixXd*>& matrices) {
  Bandwidth b;
  for (const Eigen::MatrixXd* m : matrices)
    for (Eigen::Index c = 0; c < m->cols(); ++c)
      for (Eigen::Index r = 0; r < m->rows(); ++r)
        if ((*m)(r, c) != 0.0) {
          b.lower = std::max(b.lower, r - c);
          b.upper = std::max(b.upper, c - r);
        }
  return b;
}

bool band_pays(Eigen::Index n, const Bandwidth& band) {
  if (n < 32) return false;
  const double dense = static_cast<double>(n) * static_cast<double>(n) * static_cast<double>(n) / 3.0;
  const double banded = static_cast<double>(n) * static_cast<double>(band.lower) *
                        static_cast<double>(2 * band.lower + band.upper + 1);
  return banded < dense / 2;
}

void BandLu::resize(Eigen::Index n, const Bandwidth& band) {
  n_ = n;
  band_ = band;
  kv_ = band.lower + band.upper;
  ab_.resize(2 * band.lower + band.upper + 1, n);
  pivot_.resize(static_cast<std::size_t>(n));
  inverse_.resize(static_cast<std::size_t>(n));
}

void BandLu::set_zero() { ab_.setZero(); }

double BandLu::factor() {
  const Eigen::Index kl = band_.lower, ku = band_.upper;
  double smallest = std::numeric_limits<double>::infinity(), largest = 0;
  bool singular = false;
  // The kl rows above the band hold fill-in from the interchanges: zero before the factorisation (LAPACK gbtf2).
  for (Eigen::Index c = 0; c < n_; ++c)
    for (Eigen::Index i = 0; i < kl; ++i) ab_(i, c) = 0.0;
  Eigen::Index ju = 0;  // the last column that the interchanges so far reach
  for (Eigen::Index j = 0; j < n_; ++j) {
    const Eigen::Index km = std::min(kl, n_ - 1 - j);
    Eigen::Index jp = 0;
    double best = norm2(ab_(kv_, j));
    for (Eigen::Index i = 1; i <= km; ++i)
      if (norm2(ab_(kv_ + i, j)) > best) best = norm2(ab_(kv_ + i, j)), jp = i;
    pivot_[static_cast<std::size_t>(j)] = j + jp;
    const double magnitude = std::sqrt(best);
    smallest = std::min(smallest, magnitude);
    largest = std::max(largest, magnitude);
    if (best == 0 || !std::isfinite(best)) {
      singular = true;
      inverse_[static_cast<std::size_t>(j)] = 0;
      continue;
    }
    ju = std::max(ju, std::min(j + ku + jp, n_ - 1));
    if (jp != 0)
      for (Eigen::Index c = j; c <= ju; ++c) std::swap(at(j + jp, c), at(j, c));
    const cd inv = reciprocal(ab_(kv_, j));
    inverse_[static_cast<std::size_t>(j)] = inv;
    cd* const l = &ab_(kv_, j);  // l[i] = L(j + i, j): contiguous in the column
    for (Eigen::Index i = 1; i <= km; ++i) l[i] *= inv;
    for (Eigen::Index c = j + 1; c <= ju; ++c) {
      cd* const a = &at(j, c);   // a[i] = entry (j + i, c): contiguous too
      const cd u = a[0];
      if (u == 0.0) continue;
      for (Eigen::Index i = 1; i <= km; ++i) a[i] -= l[i] * u;
    }
  }
  if (n_ == 0) return 1;
  return singular ? 0 : smallest / largest;
}

void BandLu::solve(Matrix& x) const {
  const Eigen::Index kl = band_.lower;
  for (Eigen::Index col = 0; col < x.cols(); ++col) {
    cd* b = &x(0, col);
    for (Eigen::Index j = 0; j < n_; ++j) {  // L, with the interchanges in the order they were made
      const Eigen::Index p = pivot_[static_cast<std::size_t>(j)];
      if (p != j) std::swap(b[p], b[j]);
      const Eigen::Index km = std::min(kl, n_ - 1 - j);
      const cd* const l = &ab_(kv_, j);
      const cd bj = b[j];
      for (Eigen::Index i = 1; i <= km; ++i) b[j + i] -= l[i] * bj;
    }
    for (Eigen::Index j = n_ - 1; j >= 0; --j) {  // U, upper band kv
      b[j] *= inverse_[static_cast<std::size_t>(j)];
      const cd* const u = column_offset(j);  // u[i] = U(i, j) for i >= j - kv
      const cd bj = b[j];
      for (Eigen::Index i = std::max<Eigen::Index>(0, j - kv_); i < j; ++i) b[i] -= u[i] * bj;
    }
  }
}

void BandLu::solve_transposed(Matrix& x) const {
  const Eigen::Index kl = band_.lower;
  for (Eigen::Index col = 0; col < x.cols(); ++col) {
    cd* b = &x(0, col);
    for (Eigen::Index j = 0; j < n_; ++j) {  // U^T z = b
      cd s = b[j];
      const cd* const u = column_offset(j);  // u[i] = U(i, j) for i >= j - kv
      for (Eigen::Index i = std::max<Eigen::Index>(0, j - kv_); i < j; ++i) s -= u[i] * b[i];
      b[j] = s * inverse_[static_cast<std::size_t>(j)];
    }
    for (Eigen::Index j = n_ - 1; j >= 0; --j) {  // L^T, the interchanges undone in reverse
      const Eigen::Index km = std::min(kl, n_ - 1 - j);
      cd s = b[j];
      const cd* const l = &ab_(kv_, j);
      for (Eigen::Index i = 1; i <= km; ++i) s -= l[i] * b[j + i];
      b[j] = s;
      const Eigen::Index p = pivot_[static_cast<std::size_t>(j)];
      if (p != j) std::swap(b[p], b[j]);
    }
  }
}

}  // namespace mbgen::detail
