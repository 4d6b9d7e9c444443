#include "mbgen/estimation/identifiability.hpp"

#include "numerics/row_block_qr.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace mbgen {

int IdentifiabilityAnalysis::rank() const {
  return static_cast<int>(std::count(identifiable.begin(), identifiable.end(), true));
}

IdentifiabilityAnalysis analyse_identifiability(const Eigen::MatrixXd& J, const IdentifiabilityOptions& options) {
  const Eigen::Index k = J.cols();
  IdentifiabilityAnalysis a;
  a.column_norms = J.colwise().norm().transpose();
  a.identifiable.assign(static_cast<std::size_t>(k), true);
  a.confounded_with.assign(static_cast<std::size_t>(k), {});
  const double largest = k > 0 ? a.column_norms.maxCoeff() : 0.0;
  std::vector<int> kept;
  for (Eigen::Index j = 0; j < k; ++j) {
    const double n = a.column_norms[j];
    if (!(std::isfinite(n) && largest > 0 && n > options.zero_tolerance * largest))
      a.identifiable[static_cast<std::size_t>(j)] = false;
    else
      kept.push_back(static_cast<int>(j));
  }
  if (kept.empty()) {
    a.singular_values = Eigen::VectorXd();
    return a;
  }
  // A tall Jacobian (many residuals: an FRF fit has thousands of rows per parameter) is first reduced to the
  // triangular factor of its kept columns, J_kept = Q R: any subset of R's columns has the singular values and
  // right singular vectors of the same subset of J's, so every SVD below works on k x k instead of rows x k, and
  // the one QR works on blocks of rows in cache (row_block_qr.hpp; the SVD's own column-pivoting QR does not).
  // Columns index J's through `position`.
  const Eigen::Index rows = J.rows();
  Eigen::MatrixXd reduced;
  std::vector<Eigen::Index> position(static_cast<std::size_t>(k), -1);
  for (std::size_t c = 0; c < kept.size(); ++c) position[static_cast<std::size_t>(kept[c])] = static_cast<Eigen::Index>(c);
  const bool reduce = rows > 2 * static_cast<Eigen::Index>(kept.size());
  if (reduce) {
    Eigen::MatrixXd Jk(rows, static_cast<Eigen::Index>(kept.size()));
    for (std::size_t c = 0; c < kept.size(); ++c) Jk.col(static_cast<Eigen::Index>(c)) = J.col(kept[c]);
    Eigen::VectorXd unused;
    estimation::row_block_qr(Jk, Eigen::VectorXd::Zero(rows), reduced, unused);
  }
  auto unit_columns = [&](const std::vector<int>& cols) {
    Eigen::MatrixXd U(reduce ? reduced.rows() : rows, static_cast<Eigen::Index>(cols.size()));
    for (std::size_t c = 0; c < cols.size(); ++c) {
      const double norm = a.column_norms[cols[c]];
      if (reduce)
        U.col(static_cast<Eigen::Index>(c)) = reduced.col(position[static_cast<std::size_t>(cols[c])]) / norm;
      else
        U.col(static_cast<Eigen::Index>(c)) = J.col(cols[c]) / norm;
    }
    return U;
  };
  bool first = true;
  while (!kept.empty()) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(unit_columns(kept), Eigen::ComputeThinV);
    const Eigen::VectorXd s = svd.singularValues();
    if (first) {
      a.singular_values = s;
      first = false;
    }
    // With fewer rows than columns the missing singular values are zero.
    const Eigen::Index m = static_cast<Eigen::Index>(kept.size());
    const bool short_rank = s.size() < m;
    const double ratio = short_rank ? 0.0 : s[m - 1] / s[0];
    if (!short_rank && ratio >= options.rank_tolerance) break;
    Eigen::VectorXd v;
    if (short_rank) {
      // A null vector exists beyond the computed ones: take it from the full SVD.
      const Eigen::JacobiSVD<Eigen::MatrixXd> full(unit_columns(kept), Eigen::ComputeFullV);
      v = full.matrixV().col(m - 1);
    } else {
      v = svd.matrixV().col(m - 1);
    }
    Eigen::Index worst = 0;
    for (Eigen::Index i = 0; i < m; ++i)
      if (std::abs(v[i]) >= std::abs(v[worst]) * (1 - 1e-9)) worst = i;  // ties: the later column
    const double vmax = std::abs(v[worst]);
    const int removed = kept[static_cast<std::size_t>(worst)];
    a.identifiable[static_cast<std::size_t>(removed)] = false;
    for (Eigen::Index i = 0; i < m; ++i) {
      if (i == worst || std::abs(v[i]) < 0.1 * vmax) continue;
      const int other = kept[static_cast<std::size_t>(i)];
      a.confounded_with[static_cast<std::size_t>(removed)].push_back(other);
      a.confounded_with[static_cast<std::size_t>(other)].push_back(removed);
    }
    kept.erase(kept.begin() + worst);
  }
  for (auto& c : a.confounded_with) {
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
  return a;
}

}  // namespace mbgen
