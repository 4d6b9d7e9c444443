// state_space_form for double and long double, compiled once here (the header declares them extern).
#define MBGEN_STATE_SPACE_FORM_INSTANTIATE
#include "mbgen/state_space_form.hpp"

namespace mbgen {

MBGEN_STATE_SPACE_FORM_INSTANTIATION(, double)
MBGEN_STATE_SPACE_FORM_INSTANTIATION(, long double)

}  // namespace mbgen
