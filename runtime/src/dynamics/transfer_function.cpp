// The run-time transfer-function routines for double and long double, compiled once here (the header declares
// them extern): see mbgen/transfer_function.hpp.
#define MBGEN_TRANSFER_FUNCTION_INSTANTIATE
#include "mbgen/transfer_function.hpp"

namespace mbgen {

MBGEN_TRANSFER_FUNCTION_INSTANTIATIONS(, double)
MBGEN_TRANSFER_FUNCTION_INSTANTIATIONS(, long double)

}  // namespace mbgen
