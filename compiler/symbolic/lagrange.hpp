// Lagrange's method, linearized about q = 0 (thesis Sec. 3.2-3.4; internal). Each step adds its terms to the
// matrices of `out`, which must be sized n x n (M, C, G, K), n x inputs (B) and outputs x n (Cd, Cv, Ca).
#pragma once

#include "symbolic/mechanism.hpp"
#include "symbolic/symbolic_model.hpp"

namespace mbgen::symbolic {

// Kinetic energy T = sum 1/2 m |v|^2 + 1/2 w^T J(q) w:  M = d2T/dqd dqd at 0; for spinning bodies also the
// gyroscopic G_ij = d2T/(dqd_i dq_j) - d2T/(dq_i dqd_j) and the centrifugal stiffness -d2T/dq dq at 0.
void add_kinetic_energy(const Mechanism& m, SymbolicModel& out);
// Potential energy V and dissipation function D of the spring-dampers: K = d2V/dq dq, C = d2D/dqd dqd at 0.
void add_spring_dampers(const Mechanism& m, SymbolicModel& out);
// Generalized forces of the inputs (B) and the output rows (Cd, Cv, Ca).
void add_inputs_outputs(const Mechanism& m, SymbolicModel& out);

}  // namespace mbgen::symbolic
