// The eigendecomposition of a model's state matrix A = [[0, I], [-M^-1 K, -M^-1 C]], with its modes listed as
// `mbgen inspect` (modal_analysis) lists them: one per conjugate pair (Im lambda > 0) and one per real eigenvalue,
// sorted by frequency, then damping, by the same eigensolver as modal_analysis (with the velocity block scaled
// rather than the matrix balanced). Right and left eigenvectors serve residues (modal_pairing) and eigenvalue
// derivatives (sensitivity).
#pragma once

#include <Eigen/Core>

#include <vector>

#include "mbgen/model.hpp"
#include "mbgen/dynamics/state_space.hpp"

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

// Eigenvalue e's term in every output/input channel's response at its frequency w (|Im lambda_e|; |lambda_e| for
// a real eigenvalue), from the exact partial fractions H(s) = D + sum_k C v_k w_k^T B / (s - lambda_k):
// |R/(iw - lambda_e) + conj(R)/(iw - conj(lambda_e))| with R = C v_e w_e^T B (the conjugate term only when
// lambda_e is complex), the whole |H(iw)| beside it, and the mode's visibility in each channel, share = term /
// response (0 where the response is 0). All outputs x inputs. One per index of `eigenvalues` (indices into
// sm.lambda), in that order. The one computation of how well a mode shows at the sensors: the sensitivity's
// mode visibility and the diagnosis's new-body modes both read it.
struct ModeTerm {
  double w = 0;
  Eigen::MatrixXd term, response, share;
};
std::vector<ModeTerm> mode_terms(const StateModes& sm, const std::vector<Eigen::Index>& eigenvalues);

}  // namespace mbgen
