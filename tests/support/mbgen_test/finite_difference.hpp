// Central differences, against which the tests check analytic derivatives: (f(p + h e_i) - f(p - h e_i)) / 2h for
// an f of a parameter vector that returns an Eigen vector or matrix (any scalar), or a std::vector of them.
// Header-only; include from *_test.cpp files only.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

namespace mbgen::test {

// The usual step for a parameter of value `value`: `relative` times its magnitude, or times `floor` for smaller
// values (a parameter at 0 still moves).
inline double central_step(double value, double relative = 1e-6, double floor = 1.0) {
  return relative * std::max(std::abs(value), floor);
}

template <class T>
T difference_quotient(const T& up, const T& down, double h) {
  return T((up - down) / (2 * h));
}
template <class T>
std::vector<T> difference_quotient(const std::vector<T>& up, const std::vector<T>& down, double h) {
  std::vector<T> out;
  for (std::size_t k = 0; k < up.size(); ++k) out.push_back(difference_quotient(up[k], down[k], h));
  return out;
}

// d f / d p_i at p, by central differences with step h.
template <class F>
auto central_difference(const F& f, const Eigen::VectorXd& p, Eigen::Index i, double h) {
  using Result = std::decay_t<decltype(f(p))>;
  Eigen::VectorXd plus = p, minus = p;
  plus[i] += h;
  minus[i] -= h;
  const Result up = f(plus), down = f(minus);
  return difference_quotient(up, down, h);
}

// The Jacobian of a vector-valued f at p with respect to the parameters `cols` (column j: p[cols[j]]), each
// differenced with the step `step(p[cols[j]])`.
template <class F, class Step>
Eigen::MatrixXd central_difference_jacobian(const F& f, const Eigen::VectorXd& p, const std::vector<int>& cols,
                                            const Step& step) {
  Eigen::MatrixXd J;
  for (std::size_t j = 0; j < cols.size(); ++j) {
    const Eigen::VectorXd column = central_difference(f, p, cols[j], step(p[cols[j]]));
    if (j == 0) J.resize(column.size(), static_cast<Eigen::Index>(cols.size()));
    J.col(static_cast<Eigen::Index>(j)) = column;
  }
  return J;
}

}  // namespace mbgen::test
