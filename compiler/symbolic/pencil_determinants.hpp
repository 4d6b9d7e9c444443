// Exact determinants of a quadratic pencil P(s) = M s^2 + C s + K with rational entries, and of its bordered
// matrices [[P, b], [c(s), 0]], in time polynomial in the size (internal; used by transfer_functions).
//
// GiNaC's matrix::determinant expands minors, exponential in the size: a 48-coordinate block took minutes and a
// 96-coordinate one never finished. Here instead, for each of enough word-sized primes p:
//   - P(s) is evaluated at the 2n + 1 points s = 1, ..., 2n + 1 modulo p (each polynomial has degree <= 2n);
//   - at each point one LU factorization in band storage gives det P(s) as the product of the pivots and, with a
//     solve x = P(s)^-1 b per input, each numerator c(s) adj(P(s)) b = det P(s) c(s) x;
//   - the values are interpolated (Newton's divided differences) into coefficients modulo p,
// and the coefficients are put together by the Chinese remainder theorem. The number of primes comes from a
// proven bound (Hadamard's inequality on the unit circle, where |coefficient| <= max |polynomial|), so the result
// is exact, not probable. Rows are scaled to integers first (by the least common multiple of their denominators),
// which changes each determinant by a known factor.
//
// The band: the coordinates are renumbered by reverse Cuthill-McKee when that narrows the band of the sparsity
// pattern of M, C and K (the determinant is unchanged by a symmetric renumbering, the numerators too if b and c
// are renumbered alike). A chain of bodies has a band of two bodies' coordinates, so a point costs O(n w^2)
// instead of O(n^3). Elimination is without pivoting (a zero pivot modulo a 62-bit prime is a rare accident,
// then that point is redone densely with row pivoting).
//
// Cost: O(n * L * n w^2) word operations for L primes, L proportional to n (the coefficients' size grows with n):
// cubic in n for a banded chain.
#pragma once

#include <cln/rational.h>

#include <cstdint>
#include <vector>

namespace mbgen::symbolic {

struct RationalPencil {
  int n = 0;
  std::vector<cln::cl_RA> M, C, K;              // n x n, row-major
  std::vector<std::vector<cln::cl_RA>> inputs;  // columns b, n entries each
  struct OutputRow {
    std::vector<cln::cl_RA> d, v, a;  // c(s) = d + v s + a s^2, n entries each
  };
  std::vector<OutputRow> outputs;
};

struct PencilPolynomials {
  std::vector<cln::cl_RA> determinant;  // det P(s), ascending powers of s, 2n + 1 entries (trailing zeros kept)
  // numerators[o][u] = c_o(s) adj(P(s)) b_u = -det [[P, b_u], [c_o, 0]], ascending, 2n + 1 entries
  std::vector<std::vector<std::vector<cln::cl_RA>>> numerators;
};

// Exact polynomials (see above).
PencilPolynomials exact_polynomials(const RationalPencil& pencil);

// The same polynomials modulo the prime modular::prime(k) alone, of the row-scaled pencil (each determinant times
// a non-zero integer that is not divisible by the prime when `ok`): plain residues, for cheap certificates such
// as the absence of a common factor. `ok` is false when the prime divides a row's scale factor.
struct ModularPolynomials {
  bool ok = false;
  std::uint64_t prime = 0;
  std::vector<std::uint64_t> determinant;
  std::vector<std::vector<std::vector<std::uint64_t>>> numerators;
};
ModularPolynomials modular_polynomials(const RationalPencil& pencil, int prime_index);

// Degree of gcd(a, b) modulo p for polynomials given by plain residues in ascending order (-1 if both are zero).
int gcd_degree_modulo(std::vector<std::uint64_t> a, std::vector<std::uint64_t> b, std::uint64_t p);

}  // namespace mbgen::symbolic
