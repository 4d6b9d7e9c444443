// Polynomials in the delay operator q^-1 for the ARMAX search (armax.hpp): a vector p = [p_1 .. p_m] stands for
// 1 + p_1 q^-1 + ... + p_m q^-m; filtering by it and by its inverse, products, and the second-order sections the
// search moves A and C in. Internal header.
#pragma once

#include <Eigen/Core>

namespace mbgen::methods {

// x <- x / P(q) in place, zero pre-sample values: x(k) -= sum_l p_l x(k-l).
void divide_by(const Eigen::VectorXd& p, Eigen::VectorXd& x);

// P(q) x, zero pre-sample values.
Eigen::VectorXd multiply_by(const Eigen::VectorXd& p, const Eigen::VectorXd& x);

// (1 + p q^-1 ...) (1 + r q^-1 ...)
Eigen::VectorXd product(const Eigen::VectorXd& p, const Eigen::VectorXd& r);

// A polynomial of degree n in q^-1 as floor(n/2) second-order sections 1 + s_1 q^-1 + s_2 q^-2 and, for odd n, one
// first-order section 1 + s_1 q^-1, their coefficients one after the other. The polynomial's coefficients are a
// badly conditioned description of clustered roots near z = 1 (lightly damped modes sampled fast: the spindle's
// order 10 at 8192 Hz), on which Gauss-Newton crept by 1e-5 of the cost per step; a section is one pole pair.
struct Sections {
  int n = 0;
  int count() const { return (n + 1) / 2; }
  int offset(int k) const { return 2 * k; }
  int order(int k) const { return 2 * k + 1 < n ? 2 : n - 2 * k; }
};

// Section k's coefficients.
Eigen::VectorXd section(const Sections& S, const Eigen::VectorXd& v, int k);

// The polynomial of all sections but `skip` (-1: all).
Eigen::VectorXd polynomial_of(const Sections& S, const Eigen::VectorXd& v, int skip = -1);

// Sections of 1 + p_1 q^-1 + ... + p_n q^-n from its roots: conjugate pairs, then the real roots in pairs (by
// value), the last real root alone for odd n.
Eigen::VectorXd sections_of(const Eigen::VectorXd& p);

// The sections' roots outside the unit circle reflected to 1 / conj(z) (the same spectrum up to a constant factor,
// a stable filter). Returns how many roots were reflected.
int reflect(const Sections& S, Eigen::VectorXd& v);

// |z| of the root of 1 + p_1 z^-1 + ... nearest the unit circle from inside (the largest); 0 for no root.
double largest_root(const Eigen::VectorXd& p);

}  // namespace mbgen::methods
