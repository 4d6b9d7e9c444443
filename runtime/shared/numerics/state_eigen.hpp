// Internal: the eigendecomposition of a continuous-time state matrix, the one solver behind the model's modes
// (modal_analysis, state_modes, the methods' modal truncation).
#pragma once

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace mbgen::numerics {

enum class EigenVectors { none, right, right_and_left };

// The diagonal similarity applied before the iteration (it changes no eigenvalue; the eigenvectors are scaled back
// to A's coordinates). A mechanical state matrix holds M^-1 K ~ 1e9 next to its identity block, and Eigen's
// EigenSolver does not balance.
// - balance: Parlett-Reinsch (balance.hpp), by powers of two, so exact; for any matrix. modal_analysis's and the
//   methods' choice.
// - velocity_block: for A = [[0, I], [-M^-1 K, -M^-1 C]] only: the state [q; q'/s] with s the square root of the
//   largest |M^-1 K| entry (at least 1), which makes the two blocks comparable. state_modes's choice: balancing
//   there moves the modal method's fits by rounding (its repeatability checks in modal_fit_test fail).
enum class Scaling { balance, velocity_block };

struct StateEigen {
  Eigen::VectorXcd lambda;  // every eigenvalue of A
  Eigen::MatrixXcd right;   // columns: right eigenvectors of A (empty for EigenVectors::none)
  Eigen::MatrixXcd left;    // rows: left eigenvectors, left * right = I (only for EigenVectors::right_and_left)
};

// Eigenvalues (and eigenvectors) of A after the given scaling. Eigen's real Schur form gives real eigenvalues an
// imaginary part of exactly 0 and complex ones in conjugate pairs. nullopt when the iteration does not converge.
// A must be finite (callers say which model values overflowed).
std::optional<StateEigen> state_eigen(const Eigen::MatrixXd& A, EigenVectors vectors,
                                      Scaling scaling = Scaling::balance);

// The modes of a state matrix as `mbgen inspect` lists them: indices into lambda of one eigenvalue per conjugate
// pair (Im lambda > 0) and of every real one, sorted by frequency |lambda| / 2 pi, then by damping ratio.
std::vector<Eigen::Index> listed_modes(const Eigen::VectorXcd& lambda);

}  // namespace mbgen::numerics
