// The model's modes: modal analysis of M q'' + C q' + K q = 0 (experimental modal analysis of measured data is
// mbgen/modal_identification/).
//
// modal_analysis solves the state-space eigenproblem of x = [q; q'],
//   A = [[0, I], [-M^-1 K, -M^-1 C]],
// and returns one Mode per complex-conjugate pair (the member with positive imaginary part) plus one Mode per
// real eigenvalue (overdamped or rigid-body motion: these have no conjugate partner and are reported on their
// own, with zeta = 1 for a negative real eigenvalue, 0 for an exactly zero one and -1 for a positive one).
// Modes are sorted by f_hz = |lambda| / (2 pi), ties by zeta; zeta = -Re(lambda) / |lambda|.
// The shape is the displacement part (first n entries) of the state eigenvector, scaled so that its entry of
// largest magnitude is exactly 1 (a deterministic normalisation, independent of the eigen solver's phase).
#pragma once

#include <Eigen/Core>

#include <complex>
#include <vector>

namespace mbgen {

struct Mode {
  double f_hz = 0;
  double zeta = 0;
  std::complex<double> eigenvalue;
  Eigen::VectorXcd shape;
};

// Throws DynamicsError for non-square or mismatched matrices or a singular M.
std::vector<Mode> modal_analysis(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K);

// Undamped natural frequencies in Hz, ascending, from the generalised symmetric eigenproblem K v = w^2 M v
// (M symmetric positive definite, K symmetric; only the symmetric parts are used). Eigenvalues w^2 that round
// to slightly negative values (rigid-body modes) are reported as 0 Hz.
Eigen::VectorXd undamped_natural_frequencies_hz(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K);

// Modal assurance criterion MAC(i, j) = |a_i^H b_j|^2 / ((a_i^H a_i)(b_j^H b_j)) between the columns of a and b
// (same number of rows). Zero columns give MAC 0.
Eigen::MatrixXd modal_assurance_criterion(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& b);
Eigen::MatrixXd modal_assurance_criterion(const std::vector<Mode>& a, const std::vector<Mode>& b);

}  // namespace mbgen
