// Internal: the sparse derivative entries of one parameter as dense matrices, for algorithms (state space,
// discretisation) whose cost is dominated by dense products anyway.
#pragma once

#include "mbgen/model.hpp"

#include <vector>

namespace mbgen::detail {

// result[i] holds dM/dp_i, ..., dCa/dp_i as dense matrices sized like m (entries with the same index add up).
std::vector<ModelMatrices> dense_derivatives(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count);

}  // namespace mbgen::detail
