// The eigendecomposition of a model's state matrix A = [[0, I], [-M^-1 K, -M^-1 C]], with its modes listed as
// `mbgen inspect` (modal_analysis) lists them: one per conjugate pair (Im lambda > 0) and one per real eigenvalue,
// sorted by frequency, then damping. Right and left eigenvectors serve residues (modal_pairing) and eigenvalue
// derivatives (sensitivity).
#pragma once

#include <Eigen/Core>

#include <vector>

#include "mbgen/model.hpp"
#include "mbgen/state_space.hpp"

namespace mbgen {

struct StateModes {
  StateSpace ss;
  Eigen::VectorXcd lambda;          // every eigenvalue of A
  Eigen::MatrixXcd right;           // columns: right eigenvectors, in the state coordinates [q; q']
  Eigen::MatrixXcd left;            // rows: left eigenvectors, left * right = I
  std::vector<Eigen::Index> modes;  // indices into lambda of the listed modes, in order

  double f_hz(Eigen::Index e) const;
  double zeta(Eigen::Index e) const;
};

// Throws DynamicsError for a singular M, std::runtime_error when the eigenvalue iteration fails.
StateModes state_modes(const ModelMatrices& m);

}  // namespace mbgen
