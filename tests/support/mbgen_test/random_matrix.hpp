// Random complex matrices with standard normal real and imaginary parts, filled column by column: the inputs of the
// LU tests' comparisons with Eigen. Header-only; include from *_test.cpp files only.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <random>

namespace mbgen::test {

inline Eigen::MatrixXcd random_complex_matrix(Eigen::Index rows, Eigen::Index cols, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXcd a(rows, cols);
  for (Eigen::Index c = 0; c < cols; ++c)
    for (Eigen::Index r = 0; r < rows; ++r) a(r, c) = std::complex<double>(normal(rng), normal(rng));
  return a;
}

}  // namespace mbgen::test
