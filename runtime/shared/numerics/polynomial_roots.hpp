// Internal: the roots of a real polynomial, the one root finder of the runtime and the compiler.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <vector>

namespace mbgen::numerics {

// Roots of sum_k c[k] s^k (ascending powers), leading (highest) zero coefficients dropped; roots at zero (lowest
// zero coefficients) exactly 0. The variable is first scaled by |c0 / cn|^(1/n) so that the companion matrix's
// entries are of similar size: mechanical coefficients span 1e0 .. 1e35, and without the scaling the companion's
// eigenvalues lose digits to its norm. The roots are the eigenvalues of that companion matrix (Eigen's real Schur
// form: real roots with an imaginary part of exactly 0, complex ones in conjugate pairs). Empty for a constant.
std::vector<std::complex<double>> polynomial_roots(const Eigen::VectorXd& c);

}  // namespace mbgen::numerics
