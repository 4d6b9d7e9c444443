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
// Noise in X is noise in the regressors c_i, and ordinary least squares is then biased: E[G] = G0 + Sigma, with G
// the normal matrix and Sigma the noise's contribution (Sigma_ik = E Re <Z_i dX, Z_k dX>, whitened), which pulls the
// solution towards smaller |p| (errors in variables). The solver therefore uses generalized total least squares:
// the parameters minimise theta^T G theta / theta^T Sigma theta (theta = [p; 1]), the smallest generalized
// eigenvalue lambda of (G, Sigma), which is the noise's scale (1 when the noise shape is also its level). That
// estimate is consistent when the shape of the noise is right; ordinary LS is also returned for comparison. The
// end-term unknowns of time records are exact columns, eliminated first (their Schur complement).
#pragma once

#include "direct_equations.hpp"

#include "mbgen/identifiability.hpp"

#include <Eigen/Core>

#include <vector>

namespace mbgen::methods {

struct DirectSolution {
  Eigen::VectorXd values;     // all parameters: the free ones solved for, the others as in the reference
  Eigen::VectorXd ls_values;  // the same by ordinary (weighted) least squares, for comparison
  Eigen::MatrixXd covariance; // of the free parameters, physical units (first order)
  bool total = false;         // the GTLS solution (false: LS, e.g. noise-free data whose equations hold exactly)
  double noise_scale = 0;     // lambda: the whitened equation error's variance per complex equation
  double equation_rms = 0;    // sqrt(whitened error^2 / complex equations) at the solution
  double relative_equation_error = 0;  // |e| / |(i w)^r B F| over all blocks, unweighted, at the solution
  double condition = 0;       // of the column-scaled whitened equation matrix (free parameters, end terms removed)
  long equations = 0;         // real equations
  IdentifiabilityAnalysis identifiability;  // of the free parameters' whitened columns
};

// `free`: model indices of the parameters solved for; `reference`: all parameters (the linearisation and
// weighting point; the others are known there). Each data set's `# set` values override it for that set's blocks,
// and a parameter set there is known in them. `use_total` false: ordinary least squares only.
DirectSolution solve_direct(const Model& model, const std::vector<DataSet>& data, const DirectEquations& eq,
                            const Eigen::VectorXd& reference, const std::vector<int>& free,
                            const IdentifiabilityOptions& id_options, bool use_total = true);

}  // namespace mbgen::methods
