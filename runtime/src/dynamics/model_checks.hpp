// Internal: consistency checks of ModelMatrices / ModelDerivatives against each other.
#pragma once

#include "mbgen/model.hpp"

namespace mbgen::detail {

// Checks that M, C, K are n x n, B is n x inputs and Cd, Cv, Ca are outputs x n; throws DynamicsError naming
// `where` and the offending matrix otherwise.
void check_matrices(const ModelMatrices& m, const char* where);

// Checks every derivative entry's parameter index against parameter_count and its row/column against the sizes
// of the matching matrix in m.
void check_derivatives(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count, const char* where);

// Checks that p has as many entries as the model has parameters.
void check_parameter_vector(const Model& model, const Eigen::VectorXd& p, const char* where);

}  // namespace mbgen::detail
