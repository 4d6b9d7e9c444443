// Internal: diagonal balancing of a square matrix (Parlett-Reinsch, as LAPACK's gebal without permutations).
#pragma once

#include <Eigen/Core>

namespace mbgen::numerics {

// Returns d (powers of two, so the scaling is exact) such that diag(d)^-1 A diag(d) has rows and columns of
// comparable norms.
Eigen::VectorXd balancing_scale(const Eigen::MatrixXd& A);

}  // namespace mbgen::numerics
