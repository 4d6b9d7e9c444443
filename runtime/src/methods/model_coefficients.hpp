// The model's transfer-function coefficients for one input and its measured outputs, and their parameter
// Jacobian, for step two of the two-step method. Internal header.
//
// The input's excited block (estimation/excited_block.hpp) is the system whose determinant is the common
// denominator; transfer_function.hpp gives the coefficients (monic denominator, ascending powers) and their
// exact derivatives.
#pragma once

#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <complex>
#include <vector>

namespace mbgen::methods {

struct ModelTf {
  int block_size = 0;                        // nb: the denominator has degree 2 nb
  Eigen::VectorXd denominator;               // 2 nb + 1 entries, monic
  std::vector<Eigen::VectorXd> numerators;   // per output, 2 nb + 1 entries
  // With derivatives: d denominator / d p_free[j] = ddenominator.col(j); likewise per numerator.
  Eigen::MatrixXd ddenominator;
  std::vector<Eigen::MatrixXd> dnumerators;
};

// At the full parameter vector `values`; `free` the model indices of the parameters to differentiate by (empty: no
// derivatives). Throws what the model evaluation or the coefficient computation throws (e.g. a singular M).
ModelTf model_tf(const Model& model, const Eigen::VectorXd& values, int input, const std::vector<int>& outputs,
                 const std::vector<int>& free);

// The model's transfer functions truncated to the modes nearest `modes` (one per conjugate pair; each identified
// mode takes the nearest model mode not yet taken, nearest pairs first): D = prod over the kept modes, N_c = sum of
// their pairs 2 Re(r_ck P_k(s)) plus the feedthrough times D. For data that show fewer modes than the model has
// (modal truncation: the dropped modes' contribution in the band is taken as below the noise). block_size is the
// number of kept modes; derivatives by central differences (relative step 1e-6).
ModelTf model_tf_truncated(const Model& model, const Eigen::VectorXd& values, int input, const std::vector<int>& outputs,
                           const std::vector<std::complex<double>>& modes, const std::vector<int>& free);

// Which coefficients of the model's transfer functions are structurally non-zero: non-zero at the prior or at
// either of two deterministic perturbations of `perturbed` parameters (by +7 % and -11 %), relative to the largest
// coefficient in the variable s / omega0. Entry [0] is the denominator, [1 + c] output c's numerator.
std::vector<std::vector<bool>> structural_pattern(const Model& model, const Eigen::VectorXd& prior, int input,
                                                  const std::vector<int>& outputs, const std::vector<int>& perturbed);

}  // namespace mbgen::methods
