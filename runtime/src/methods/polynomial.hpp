// Real polynomials in ascending powers, for the two-step method's transfer functions. Internal header.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <vector>

namespace mbgen::methods {

// p(s) = sum_k c[k] s^k (Horner).
std::complex<double> poly_eval(const Eigen::VectorXd& c, std::complex<double> s);
std::complex<double> poly_eval(const Eigen::VectorXcd& c, std::complex<double> s);

// Coefficients (ascending, complex) of prod_k (s - r_k); leading coefficient 1.
Eigen::VectorXcd poly_from_roots(const std::vector<std::complex<double>>& roots);

// Modal form to coefficients: for vibration modes lambda_k (one per conjugate pair), the monic denominator
// D(s) = prod_k (s - lambda_k)(s - conj lambda_k) (2m + 1 entries) and the 2m x 2m matrix T whose columns map
// (Re r_k, Im r_k) to the numerator coefficients (ascending) of sum_k r_k / (s - lambda_k) + conj: the pair's
// numerator is 2 Re(r_k P_k(s)), P_k = D(s) / (s - lambda_k).
struct ModalPolynomials {
  Eigen::VectorXd denominator;
  Eigen::MatrixXd residue_map;
};
ModalPolynomials modal_polynomials(const std::vector<std::complex<double>>& modes);

}  // namespace mbgen::methods
