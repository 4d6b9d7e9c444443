// Time simulation of M q'' + C q' + K q = B u from rest (q = q' = 0 at the first sample) for uniformly sampled
// force records, and the exact sensitivities of the simulated outputs with respect to the parameters.
//
// Records are matrices with one row per sample: inputs (samples x inputs) in, outputs (samples x outputs) out.
// The input between samples is held (InputHold::ZeroOrder) or interpolated linearly (InputHold::FirstOrder,
// for `# hold=none` records); see state_space.hpp. Output k is y(t_0 + k dt) = C x_k + D u_k.
//
// Sensitivities (choice documented here): forward sensitivities of the *discretised* system,
//   s_{k+1} = Phi s_k + dPhi x_k + dGamma0 u_k + dGamma1 u_{k+1},   dy_k = C s_k + dC x_k + dD u_k,
// where dPhi, dGamma0, dGamma1 are the exact derivatives of the discretisation (block-triangular matrix
// exponential, discretize_derivatives). dy/dp is therefore the exact derivative of the simulated outputs
// themselves (not of a differently discretised continuous sensitivity equation), which is what a gradient-
// based output-error estimator needs for consistent gradients. All parameters are propagated together: the
// state sensitivities form one (states x parameters) matrix per step, so each step costs two dense products.
#pragma once

#include "mbgen/model.hpp"
#include "mbgen/dynamics/state_space.hpp"

#include <Eigen/Core>

#include <vector>

namespace mbgen {

// Outputs (samples x outputs) of the discrete system for inputs (samples x inputs), zero initial state.
Eigen::MatrixXd simulate(const DiscreteStateSpace& system, const Eigen::MatrixXd& inputs);

// Discretises M, C, K, B, Cd, Cv, Ca with interval dt and the given hold, then simulates.
Eigen::MatrixXd simulate(const ModelMatrices& m, const Eigen::MatrixXd& inputs, double dt, InputHold hold);
Eigen::MatrixXd simulate(const Model& model, const Eigen::VectorXd& p, const Eigen::MatrixXd& inputs, double dt,
                         InputHold hold);

struct SimulationSensitivity {
  Eigen::MatrixXd outputs;                // samples x outputs
  std::vector<Eigen::MatrixXd> doutputs;  // doutputs[i] = d outputs / d p_i, samples x outputs
};

SimulationSensitivity simulate_with_sensitivity(const ModelMatrices& m, const ModelDerivatives& d,
                                                int parameter_count, const Eigen::MatrixXd& inputs, double dt,
                                                InputHold hold);
SimulationSensitivity simulate_with_sensitivity(const Model& model, const Eigen::VectorXd& p,
                                                const Eigen::MatrixXd& inputs, double dt, InputHold hold);

}  // namespace mbgen
