// The result of the symbolic stage: exact equations of motion of a model, ready for the emitters.
//
//   M q'' + (C + G) q' + K q = B u,      y = Cd q + Cv q' + Ca q''
//
// All expressions are GiNaC expressions over the symbols of the *free* parameters (derived parameters are
// substituted); numbers are exact rationals (or exact algebraic numbers such as sqrt(2)/2 for oblique
// directions). G (gyroscopic, skew-symmetric) is kept apart from C and also added into `C_total`.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "ir/model_ir.hpp"

namespace mbgen::symbolic {

struct FreeParameter {
  std::string name;
  GiNaC::symbol sym;
  GiNaC::ex value;  // exact rational value from the model (after --set overrides)
  const ir::Parameter* ir = nullptr;
};

// A generalized coordinate: a body's dof, or (with `state` set) a state of an output filter named `body`, which
// moves no mass: its equation is the filter's (output_filters.hpp).
struct Coordinate {
  std::string body;
  ir::Dof dof = ir::Dof::X;
  std::string state;         // a filter's state ("w", or "w1", "w2", ... for a delay's sections); empty for a body
  std::string name() const;  // "body.dof", e.g. "mass1.x", or "filter.state", e.g. "lp_d2.w"
  bool is_filter_state() const { return !state.empty(); }
};

struct TransferFunction {
  int output = 0, input = 0;  // indices into model outputs / inputs
  bool symbolic = false;      // coefficients below are exact expressions in the parameters
  std::vector<GiNaC::ex> numerator;    // ascending powers of s
  std::vector<GiNaC::ex> denominator;  // ascending powers of s, monic (last entry 1)
  std::vector<int> coordinates;        // the uncoupled block the pair lives in (coordinate indices)
  bool exact = true;  // false: the block is too large for exact coefficients; numerator and denominator are empty
                      // (the emitted code computes them at run time)
};

// An exact pole-zero cancellation found at the current parameter values (thesis Sec. 4.2, Example 1).
struct Cancellation {
  int output = 0, input = 0;
  GiNaC::ex common_factor;  // polynomial in s that divides numerator and denominator
  std::string text;
};

struct SymbolicModel {
  const ir::ModelIr* model = nullptr;
  GiNaC::symbol s{"s"};
  std::vector<FreeParameter> parameters;  // in model order, derived ones excluded
  std::vector<Coordinate> coordinates;    // in model order (bodies, then their dofs as written), then filter states
  GiNaC::matrix M, C, G, C_total, K;      // n x n
  GiNaC::matrix B;                        // n x inputs
  GiNaC::matrix Cd, Cv, Ca;               // outputs x n
  // Uncoupled blocks: a partition of the coordinate indices such that M, C_total, K are block diagonal.
  std::vector<std::vector<int>> blocks;
  std::vector<TransferFunction> transfer_functions;  // one per (output, input) pair, output-major
  std::vector<Cancellation> cancellations;

  GiNaC::exmap values() const;  // symbol -> exact value for every free parameter
  int parameter_index(const std::string& name) const;  // -1 if absent
};

}  // namespace mbgen::symbolic
