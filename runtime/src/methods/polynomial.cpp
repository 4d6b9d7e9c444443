#include "polynomial.hpp"

#include <cmath>

namespace mbgen::methods {

std::complex<double> poly_eval(const Eigen::VectorXd& c, std::complex<double> s) {
  std::complex<double> v = 0;
  for (Eigen::Index k = c.size() - 1; k >= 0; --k) v = v * s + c[k];
  return v;
}

std::complex<double> poly_eval(const Eigen::VectorXcd& c, std::complex<double> s) {
  std::complex<double> v = 0;
  for (Eigen::Index k = c.size() - 1; k >= 0; --k) v = v * s + c[k];
  return v;
}

Eigen::VectorXcd poly_from_roots(const std::vector<std::complex<double>>& roots) {
  Eigen::VectorXcd c = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(roots.size()) + 1);
  c[0] = 1;
  for (std::size_t k = 0; k < roots.size(); ++k) {
    // multiply by (s - r): new[j] = old[j-1] - r old[j]
    for (Eigen::Index j = static_cast<Eigen::Index>(k) + 1; j >= 1; --j) c[j] = c[j - 1] - roots[k] * c[j];
    c[0] = -roots[k] * c[0];
  }
  return c;
}

ModalPolynomials modal_polynomials(const std::vector<std::complex<double>>& modes) {
  std::vector<std::complex<double>> all;
  for (const auto& l : modes) {
    all.push_back(l);
    all.push_back(std::conj(l));
  }
  ModalPolynomials out;
  out.denominator = poly_from_roots(all).real();
  const Eigen::Index q = static_cast<Eigen::Index>(all.size());
  out.residue_map.resize(q, q);
  for (std::size_t k = 0; k < modes.size(); ++k) {
    std::vector<std::complex<double>> others;
    for (std::size_t j = 0; j < all.size(); ++j)
      if (j != 2 * k) others.push_back(all[j]);
    const Eigen::VectorXcd Pk = poly_from_roots(others);
    out.residue_map.col(2 * static_cast<Eigen::Index>(k)) = 2 * Pk.real();
    out.residue_map.col(2 * static_cast<Eigen::Index>(k) + 1) = -2 * Pk.imag();
  }
  return out;
}

}  // namespace mbgen::methods
