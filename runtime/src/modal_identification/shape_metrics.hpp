// Comparisons of complex shape vectors shared by the stabilization, the selection and the mode table.
#pragma once

#include <Eigen/Core>

#include <complex>

namespace mbgen::modal_detail {

// MAC of two vectors: |a^H b|^2 / ((a^H a)(b^H b)); 0 when either is zero.
inline double shape_mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  const double aa = a.squaredNorm(), bb = b.squaredNorm();
  if (aa <= 0 || bb <= 0) return 0;
  return std::norm(a.dot(b)) / (aa * bb);
}

}  // namespace mbgen::modal_detail
