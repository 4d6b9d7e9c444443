// The two-step method's analytical route (a) on the compiler side: the model's transfer-function coefficients as the
// exact expressions the compiler derives (symbolic/transfer_functions.hpp), set equal to symbols for the identified
// coefficients and solved by elimination (elimination.hpp) into closed forms, then evaluated at the identified
// values taken as exact rationals (a double is one). `mbgen fit --method two-step` passes make_analytical_solver to
// the runtime (mbgen/methods/two_step_analytical.hpp); docs/methods.md#two-step.
//
// Applies where every transfer function's block has at most symbolic::kMaxSymbolicBlockSize coordinates (the
// coefficients are then derived as expressions), there are at most kMaxUnknowns unknowns, and the symbolic
// coefficients agree with the runtime's at the prior (relative 1e-9; otherwise the blocks differ and the equations
// would not be the same). Square subsystems: every choice of as many equations as unknowns where there are at most
// kMaxSubsystems of them, each solved on its own (square elimination); beyond that one greedy elimination over all
// equations, the equations it does not use being the checks.
#pragma once

#include <ginac/ginac.h>
#include <mbgen/methods/two_step_analytical.hpp>

#include <memory>
#include <string>
#include <vector>

#include "symbolic/symbolic_model.hpp"

namespace mbgen::elimination {

constexpr std::size_t kMaxUnknowns = 10;
constexpr std::size_t kMaxSubsystems = 70;

// An exact solution of one square subsystem.
struct ExactSubsystem {
  std::vector<int> equations;
  std::vector<GiNaC::ex> closed_form;               // per unknown, first branch (in the coefficient symbols)
  std::vector<std::vector<GiNaC::ex>> all_forms;    // per branch, per unknown
  std::vector<std::vector<GiNaC::ex>> solutions;    // per real solution, per unknown: exact values
  std::string failure;
};

struct ExactSolution {
  std::string unavailable;
  std::vector<GiNaC::symbol> coefficients;  // per equation, named as in AnalyticalSolution::coefficient_names
  std::string subsystem_choice;
  std::vector<ExactSubsystem> subsystems;
};

// `identified`: the identified value of each of system.equations, exact. The parameters other than the unknowns are
// held at system.values (taken as exact rationals).
ExactSolution solve_exactly(const symbolic::SymbolicModel& sm, const CoefficientSystem& system,
                            const std::vector<GiNaC::numeric>& identified);

// The exact rational value of a double.
GiNaC::numeric exact(double x);

// The runtime's hook: solve_exactly with the identified doubles as exact rationals, solutions as doubles.
AnalyticalSolver make_analytical_solver(std::shared_ptr<const symbolic::SymbolicModel> sm);

}  // namespace mbgen::elimination
