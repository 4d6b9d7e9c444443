// Validity checks of derived equations of motion (internal): each throws frontend::ModelError at the body.
#pragma once

#include "symbolic/mechanism.hpp"
#include "symbolic/symbolic_model.hpp"

namespace mbgen::symbolic {

// A coordinate whose stiffness and damping rows are identically zero: no element acts on it.
void check_every_coordinate_is_held(const Mechanism& m, const SymbolicModel& sm);
// A coordinate with zero mass or inertia at the current values, then a singular mass matrix of a body (exact
// determinant at the current values).
void check_mass_matrix(const Mechanism& m, const SymbolicModel& sm);

}  // namespace mbgen::symbolic
