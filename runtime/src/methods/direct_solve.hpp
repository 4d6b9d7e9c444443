// The direct method's least squares (docs/methods.md#direct). Internal header.
//
// At a reference point p0 the equation error of every block is affine in the free parameters,
//
//     e(p) = c0 + sum_i p_i c_i (+ i w a + b),   c_i = Z_i X - (i w)^r B_i F,   Z_i = (i w)^2 dM_i + i w dC_i + dK_i,
//
// exact when M, C, K, B are linear in the parameters (then one solve is the answer), a Gauss-Newton step otherwise.
// Weighting: the block's error caused by the noise of X is Z dX, of covariance Z S S^H Z^H, so each block is
// whitened by (Z(p0) S)^-1. Near a resonance (Z small) the equations are then as trustworthy as the data say,
// and off resonance (Z large, |X| small) they do not dominate: the whitened equation error is, to first order at
// p0, the output error of the coordinates' motion. Real and imaginary parts are stacked.
//
// Noise in X is noise in the regressors c_i, and ordinary least squares is then biased (errors in variables): the
// noise's own energy in the normal matrix pulls the solution towards smaller |p|, about -0.5 % on mdof2's weakly
// coupled mass-2 parameters at 40 dB, -1.3 % on one time record. The solver removes it with instrumental variables
// (Nickel 1999 Sec. 2.2; Fritzen 1986): the instruments are the same columns built from the reference model's
// response to the measured force (noise-free, so uncorrelated with the noise), and the equations are solved in
// their span. Iterated (the reference moved to the estimate) this is the refined IV estimator; it needs no noise
// model for consistency, the whitening only sets its efficiency. Tried first and dropped: generalized total least
// squares (as consistent, but its eigenvector swung by tens of percent where a direction is weakly determined: the
// scale of mdof2's mass-2 row, fixed only through the weak coupling k12) and bias-compensated LS (G - lambda Sigma
// turned indefinite in that direction on a time record). End-term unknowns of time records are exact columns.
#pragma once

#include "direct_equations.hpp"

#include "mbgen/estimation/identifiability.hpp"

#include <Eigen/Core>

#include <vector>

namespace mbgen::methods {

struct DirectSolution {
  Eigen::VectorXd values;     // all parameters: the free ones solved for, the others as in the reference
  Eigen::VectorXd ls_values;  // the same by ordinary (weighted) least squares, for comparison
  Eigen::MatrixXd covariance; // of the free parameters, physical units (first order)
  bool instrumental = false;  // the IV solution (false: ordinary LS)
  double noise_scale = 0;     // lambda: the whitened equation error's variance per complex equation
  double equation_rms = 0;    // sqrt(whitened error^2 / complex equations) at the solution
  double relative_equation_error = 0;  // |e| / |(i w)^r B F| over all blocks, unweighted, at the solution
  double condition = 0;       // of the column-scaled whitened equation matrix (free parameters, end terms removed)
  long equations = 0;         // real equations
  IdentifiabilityAnalysis identifiability;  // of the free parameters' whitened columns
};

// `free`: model indices of the parameters solved for; `reference`: all parameters (the linearisation and
// weighting point; the others are known there). Each data set's `# set` values override it for that set's blocks,
// and a parameter set there is known in them. `instrumental` false: ordinary least squares only.
DirectSolution solve_direct(const Model& model, const std::vector<DataSet>& data, const DirectEquations& eq,
                            const Eigen::VectorXd& reference, const std::vector<int>& free,
                            const IdentifiabilityOptions& id_options, bool instrumental = true);

}  // namespace mbgen::methods
