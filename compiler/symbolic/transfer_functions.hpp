// Transfer functions G(s) = c(s) adj(P(s)) b / det P(s), P = M s^2 + C_total s + K, and exact pole-zero
// cancellations (thesis Sec. 3.3, 4.2).
#pragma once

#include <optional>

#include "symbolic/symbolic_model.hpp"

namespace mbgen::symbolic {

// Blocks up to this many coordinates get symbolic coefficients (exact expressions in the parameters); larger
// ones get exact numbers at the current values. A 3 x 3 block already gives numerators of a few hundred terms;
// the spindle's blocks (5 and 6 coordinates) would give tens of thousands.
constexpr int kMaxSymbolicBlockSize = 3;

// Exact numbers: blocks up to this many coordinates get exact rational coefficients (multimodular determinants,
// pencil_determinants.hpp; about 2 s for 96 coordinates, the cost growing like n^3). Larger blocks get none: the
// emitted code computes their coefficients at run time anyway, and their cancellations are checked modulo primes.
constexpr int kMaxExactBlockSize = 100;
// Exact numbers that are not all rational (pi, square roots) go through GiNaC's determinants, exponential in the
// size: up to this many coordinates.
constexpr int kMaxGinacBlockSize = 12;
// ... and holding at most this many distinct irrational numbers (square roots, pi, sines) at the parameters' values:
// the field they generate, in which the exact determinants are taken, doubles its degree with each square root.
constexpr std::size_t kMaxIrrationalNumbers = 3;

// The transfer function from input `input` to output `output` of a derived model (M, C_total, K, B, Cd, Cv, Ca,
// blocks filled). It is computed on the blocks where both the input and the output have entries; if there is
// none it is exactly zero (numerator {0}, denominator {1}, no coordinates).
TransferFunction transfer_function(const SymbolicModel& sm, int output, int input);

// The exact common factor of numerator and denominator at the current parameter values, if it has degree > 0
// in s. Coefficients that are not rational (pi, square roots) are treated as independent unknowns, so a
// cancellation that depends on their algebraic relations can be missed, never invented.
std::optional<Cancellation> find_cancellation(const SymbolicModel& sm, const TransferFunction& tf);

// Fills sm.transfer_functions (output-major) and sm.cancellations.
void add_transfer_functions(SymbolicModel& sm);

}  // namespace mbgen::symbolic
