// Structural / practical identifiability from a Jacobian of residuals with respect to parameters.
//
// The columns are first scaled by the caller (by the parameters' magnitudes, so that they measure relative
// sensitivity). A column whose norm is at most `zero_tolerance` times the largest is unidentifiable on its own
// (the data do not depend on the parameter at all, e.g. a y-direction stiffness under x-direction data when the
// model's blocks are uncoupled). The remaining columns are normalised to unit length and their singular values
// computed; while the smallest ratio sigma_min / sigma_max is below `rank_tolerance`, the parameter with the
// largest entry in the corresponding right singular vector (ties: the later column) is declared unidentifiable
// and removed, and the parameters with a significant entry in that vector (|v_j| >= 0.1 max |v|) are recorded as
// confounded with it (e.g. two springs that only appear as a sum: one is removed, the other then stands for the
// sum given the removed one's prior value). Never throws on rank deficiency.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace mbgen {

struct IdentifiabilityOptions {
  double zero_tolerance = 1e-10;
  double rank_tolerance = 1e-7;
};

struct IdentifiabilityAnalysis {
  Eigen::VectorXd column_norms;     // of the scaled Jacobian, per column
  Eigen::VectorXd singular_values;  // of the unit-column Jacobian of all non-zero columns, descending
  std::vector<bool> identifiable;   // per column
  std::vector<std::vector<int>> confounded_with;  // per column: the columns it is confounded with
  int rank() const;
};

IdentifiabilityAnalysis analyse_identifiability(const Eigen::MatrixXd& scaled_jacobian,
                                                const IdentifiabilityOptions& options = {});

}  // namespace mbgen
