// Exact solution of a small polynomial system by elimination (the two-step method's analytical route, thesis
// Sec. 3.6.2 (a); docs/methods.md#two-step).
//
// The equations are polynomials in the unknowns whose coefficients may hold other symbols (the identified transfer
// function coefficients: the solution is then a closed form in them). Elimination solves for the parameters that
// enter linearly in turn: an equation of degree 1 in an unknown gives it as a rational function of the others,
// which is substituted everywhere; an equation in one unknown of degree 2 splits the solution into two branches
// (the quadratic formula). Each equation is first freed of monomial factors of the unknowns (x^k = 0 would put a
// physical parameter at zero). Pivots are taken from the equations with the fewest unknowns, preferring a
// coefficient free of unknowns (no division by an expression that may vanish), then the smaller equation.
//
// Square mode (as many equations as unknowns): an equation that vanishes, or loses its unknowns before the end,
// shows the equations dependent: no closed form. Otherwise (overdetermined, greedy) such equations are the checks,
// and `pivots` records the square subsystem actually used. No closed form either when every remaining equation is
// of degree above 2 in each unknown, or non-linear in several, or when an expression outgrows `max_terms`.
#pragma once

#include <ginac/ginac.h>

#include <cstddef>
#include <string>
#include <vector>

namespace mbgen::elimination {

struct EliminationLimits {
  std::size_t max_terms = 4000;  // terms of an expanded equation
};

struct EliminationBranch {
  std::vector<GiNaC::ex> values;  // per unknown: its closed form in the other symbols
  std::vector<int> pivots;        // the equations solved, in the order used (indices into the input)
  std::vector<int> checks;        // the equations left over (greedy mode)
};

struct Elimination {
  std::string failure;  // non-empty: no closed form, and why (then no branches)
  std::vector<EliminationBranch> branches;
};

Elimination eliminate(const std::vector<GiNaC::ex>& equations, const std::vector<GiNaC::symbol>& unknowns, bool square,
                      const EliminationLimits& limits = {});

}  // namespace mbgen::elimination
