// A compiled list of GiNaC expressions: evaluated in double with no GiNaC at run time.
//
// The expressions are first rid of common subexpressions, then flattened into a tape of three-address
// instructions over a register file (registers 0..n_params-1 hold the parameters). Evaluating the tape is a
// single pass, so models changed at run time are evaluated fast without a C++ compile step.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "passes/sign_free_key.hpp"

namespace mbgen::evaluator {

// A valid expression the tape cannot compute (a parameter in an exponent): a limit of the evaluator, not a bug.
class UnsupportedExpression : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ExpressionTape {
 public:
  // `parameters` are the symbols the expressions may use, in the order evaluate() receives their values.
  ExpressionTape(const std::vector<GiNaC::symbol>& parameters, const std::vector<GiNaC::ex>& expressions);

  // Evaluates every expression at `params` into `out` (resized to the number of expressions). Thread-safe.
  void evaluate(const double* params, std::vector<double>& out) const;

  std::size_t instruction_count() const { return code_.size(); }

 private:
  enum class Op { Const, Add, Mul, Div, PowInt, PowReal, Sqrt, Sin, Cos };
  struct Instruction {
    Op op;
    int dst, a, b;  // registers
    double value;   // Const value, PowReal exponent
    int exponent;   // PowInt exponent
  };

  int compile(const GiNaC::ex& e);
  // The operands of a sum or product in the order of their sign-free keys (passes/sign_free_key.hpp), not GiNaC's
  // internal order: that order follows hash values which depend on where the program is loaded (address-space
  // randomization), and the order of a floating-point sum changes its rounding, so that two runs of one fit would
  // differ in the last digits and then, through a long iteration, in more. An operand and its negative take the
  // same place, so two runs differ at most by an exact sign.
  std::vector<GiNaC::ex> canonical_operands(const GiNaC::ex& e);
  int emit(Op op, int a, int b = -1, double value = 0, int exponent = 0);

  int n_params_ = 0;
  int n_registers_ = 0;
  std::vector<Instruction> code_;
  std::vector<int> outputs_;
  // While compiling: symbols and temporaries already in a register, and the operands' ordering keys.
  std::map<GiNaC::ex, int, GiNaC::ex_is_less> registers_;
  passes::SignFreeKeys keys_;
};

}  // namespace mbgen::evaluator
