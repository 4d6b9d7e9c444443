// State-space forms of M q'' + C q' + K q = B u, y = Cd q + Cv q' + Ca q'' (thesis Sec. 3.2), x = [q; q']:
//
//   x' = A x + B u,   y = C x + D u,
//   A = [[0, I], [-M^-1 K, -M^-1 C]],  B = [0; M^-1 B],
//   C = [Cd - Ca M^-1 K, Cv - Ca M^-1 C],  D = Ca M^-1 B   (acceleration outputs feed the input through).
//
// Discretisation with sampling interval T, exact for the assumed input between samples:
// - InputHold::ZeroOrder: u is held constant over each interval (records without a `# hold` line, docs/interfaces.md;
//   the thesis's Eq. 3.9): x[k+1] = Phi x[k] + Gamma0 u[k], Phi = e^{AT}, Gamma0 = int_0^T e^{A s} ds B.
// - InputHold::FirstOrder: u is interpolated linearly between samples (triangle hold; `# hold=none`, a
//   band-limited input sampled without hold): x[k+1] = Phi x[k] + Gamma0 u[k] + Gamma1 u[k+1].
// Both come from one matrix exponential of an augmented block matrix ([[A, B], [0, 0]] T for ZOH,
// [[A T, B T, 0], [0, 0, I], [0, 0, 0]] for FOH) after a diagonal (power-of-two) balancing of A, which keeps
// the exponential accurate when positions and velocities differ by orders of magnitude.
//
// Parameter derivatives: state_space_derivatives differentiates (A, B, C, D) analytically from the sparse
// model derivatives; discretize_derivatives differentiates (Phi, Gamma0, Gamma1) exactly via the block-triangular
// (Van Loan) exponential exp([[F, dF], [0, F]]) = [[e^F, L(F, dF)], [0, e^F]], whose corner is the Frechet
// derivative of the exponential: no finite differences anywhere.
#pragma once

#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <vector>

namespace mbgen {

struct StateSpace {
  Eigen::MatrixXd A, B, C, D;
};

enum class InputHold { ZeroOrder, FirstOrder };

// x[k+1] = Phi x[k] + Gamma0 u[k] + Gamma1 u[k+1],  y[k] = C x[k] + D u[k].  Gamma1 is zero for ZeroOrder.
struct DiscreteStateSpace {
  Eigen::MatrixXd Phi, Gamma0, Gamma1, C, D;
  double dt = 0;
  InputHold hold = InputHold::ZeroOrder;
};

// Throws DynamicsError for a singular M ("mass matrix M is singular ...") or inconsistent sizes.
StateSpace state_space(const ModelMatrices& m);

// result[i] holds dA/dp_i, dB/dp_i, dC/dp_i, dD/dp_i.
std::vector<StateSpace> state_space_derivatives(const ModelMatrices& m, const ModelDerivatives& d,
                                                int parameter_count);

// dt > 0. Throws DynamicsError for a non-positive or non-finite dt or inconsistent sizes.
DiscreteStateSpace discretize(const StateSpace& ss, double dt, InputHold hold);

// result[i] holds the derivatives of Phi, Gamma0, Gamma1, C, D with respect to p_i (dt and hold copied), given
// the continuous derivatives ds (e.g. from state_space_derivatives).
std::vector<DiscreteStateSpace> discretize_derivatives(const StateSpace& ss, const std::vector<StateSpace>& ds,
                                                       double dt, InputHold hold);

}  // namespace mbgen
