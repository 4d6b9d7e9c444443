#include "numerics/polynomial_roots.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace mbgen::numerics {

std::vector<std::complex<double>> polynomial_roots(const Eigen::VectorXd& c) {
  int n = static_cast<int>(c.size()) - 1;
  while (n >= 0 && c[n] == 0) --n;
  if (n <= 0) return {};
  // Roots at zero: factor out the lowest zero coefficients exactly.
  int low = 0;
  while (c[low] == 0) ++low;
  std::vector<std::complex<double>> roots(static_cast<std::size_t>(low), 0.0);
  const int m = n - low;
  if (m == 0) return roots;
  const double scale = std::pow(std::abs(c[low] / c[n]), 1.0 / m);
  // Monic in the scaled variable x = s / scale: coefficients c[low + k] scale^k / (c[n] scale^m).
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(m, m);
  for (int k = 0; k < m; ++k)
    companion(k, m - 1) = -c[low + k] * std::pow(scale, k - m) / c[n];
  for (int k = 1; k < m; ++k) companion(k, k - 1) = 1;
  const Eigen::EigenSolver<Eigen::MatrixXd> es(companion, false);
  for (Eigen::Index k = 0; k < m; ++k) roots.push_back(es.eigenvalues()[k] * scale);
  return roots;
}

}  // namespace mbgen::numerics
