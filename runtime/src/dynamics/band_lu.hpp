// LU factorisation with partial pivoting of a complex band matrix (kl sub-, ku superdiagonals), LAPACK's gbtf2 /
// gbtrs in buffers reused from one factorisation to the next: the dynamic stiffness P(jw) of a large model whose
// coordinates couple only to near neighbours (a chain of bodies: kl = ku = 11 for six-coordinate bodies). Costs
// O(n kl (kl + ku)) per factorisation and O(n (2 kl + ku)) per solved column instead of O(n^3) and O(n^2).
// Internal header; same interface as SmallLu (small_lu.hpp), whose results it reproduces to rounding.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <vector>

namespace mbgen::detail {

// The band of the union of the non-zero patterns of square matrices of one size.
struct Bandwidth {
  Eigen::Index lower = 0, upper = 0;
};
Bandwidth bandwidth_of(const std::vector<const Eigen::MatrixXd*>& matrices);

// Whether band storage pays for an n x n matrix of this band: n >= 32 (smaller lumped models keep the dense
// factorisation, bit for bit) and less than half the dense work.
bool band_pays(Eigen::Index n, const Bandwidth& band);

class BandLu {
 public:
  using Matrix = Eigen::MatrixXcd;

  // n x n with the given band; entries are zero until set.
  void resize(Eigen::Index n, const Bandwidth& band);
  void set_zero();
  // Entry (r, c) of the matrix to factor, |r - c| within the band.
  std::complex<double>& at(Eigen::Index r, Eigen::Index c) { return ab_(kv_ + r - c, c); }
  Eigen::Index rows() const { return n_; }
  const Bandwidth& band() const { return band_; }

  // As SmallLu::factor: row-permuted A = L U; returns the smallest over the largest |pivot| (0 if singular).
  double factor();
  void solve(Matrix& x) const;
  void solve_transposed(Matrix& x) const;

 private:
  // Column j shifted so that [i] is entry (i, j) of the matrix (valid for i within the band; the pointer stays
  // inside the buffer: j (rows - 1) + kv >= 0).
  const std::complex<double>* column_offset(Eigen::Index j) const { return ab_.data() + j * ab_.rows() + kv_ - j; }

  Eigen::Index n_ = 0, kv_ = 0;  // kv = lower + upper: the band of U after the row interchanges
  Bandwidth band_;
  Matrix ab_;                    // (2 lower + upper + 1) x n: entry (r, c) at (kv + r - c, c)
  std::vector<Eigen::Index> pivot_;
  std::vector<std::complex<double>> inverse_;
};

}  // namespace mbgen::detail
