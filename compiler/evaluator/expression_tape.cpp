#include "evaluator/expression_tape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "passes/cse.hpp"
#include "emit/ginac_text.hpp"

namespace mbgen::evaluator {

ExpressionTape::ExpressionTape(const std::vector<GiNaC::symbol>& parameters, const std::vector<GiNaC::ex>& expressions) {
  n_params_ = static_cast<int>(parameters.size());
  n_registers_ = n_params_;
  for (int i = 0; i < n_params_; ++i) {
    const GiNaC::symbol& p = parameters[static_cast<std::size_t>(i)];
    registers_.emplace(p, i);
  }
  const passes::CseResult cse = passes::eliminate_common_subexpressions(expressions, "tape_t");
  for (const auto& [sym, body] : cse.temporaries) registers_.emplace(sym, compile(body));
  for (const GiNaC::ex& e : cse.outputs) outputs_.push_back(compile(e));
  // Only needed while compiling; the tape itself holds no GiNaC object.
  registers_.clear();
  keys_ = passes::SignFreeKeys();
}

std::vector<GiNaC::ex> ExpressionTape::canonical_operands(const GiNaC::ex& e) {
  std::vector<GiNaC::ex> out;
  for (std::size_t i : keys_.operand_order(e)) out.push_back(e.op(i));
  return out;
}

int ExpressionTape::emit(Op op, int a, int b, double value, int exponent) {
  code_.push_back({op, n_registers_, a, b, value, exponent});
  return n_registers_++;
}

int ExpressionTape::compile(const GiNaC::ex& e) {
  using namespace GiNaC;
  if (auto it = registers_.find(e); it != registers_.end()) return it->second;
  if (is_a<numeric>(e) || is_a<constant>(e)) {
    const ex v = e.evalf();
    if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
      throw std::runtime_error("evaluator: a constant is not a real number");
    return emit(Op::Const, -1, -1, ex_to<numeric>(v).to_double());
  }
  if (is_a<symbol>(e)) throw std::runtime_error("evaluator: unknown symbol `" + ex_to<symbol>(e).get_name() + "`");
  if (is_a<add>(e)) {
    const std::vector<ex> terms = canonical_operands(e);
    int acc = compile(terms[0]);
    for (std::size_t i = 1; i < terms.size(); ++i) acc = emit(Op::Add, acc, compile(terms[i]));
    return acc;
  }
  if (is_a<mul>(e)) {
    const std::vector<ex> factors = canonical_operands(e);
    int acc = compile(factors[0]);
    for (std::size_t i = 1; i < factors.size(); ++i) {
      // x^-n factors become divisions: fewer roundings than a reciprocal then a product.
      const ex& f = factors[i];
      if (is_a<power>(f) && is_a<numeric>(f.op(1)) && ex_to<numeric>(f.op(1)).is_negative())
        acc = emit(Op::Div, acc, compile(pow(f.op(0), -f.op(1))));
      else
        acc = emit(Op::Mul, acc, compile(f));
    }
    return acc;
  }
  if (is_a<power>(e)) {
    const ex& expo = e.op(1);
    const int base = compile(e.op(0));
    if (is_a<numeric>(expo)) {
      const numeric n = ex_to<numeric>(expo);
      if (n.is_integer()) return emit(Op::PowInt, base, -1, 0, n.to_int());
      if (n == numeric(1, 2)) return emit(Op::Sqrt, base);
      if (n == numeric(-1, 2)) return emit(Op::Div, emit(Op::Const, -1, -1, 1.0), emit(Op::Sqrt, base));
      return emit(Op::PowReal, base, -1, n.to_double());
    }
    throw UnsupportedExpression("a power whose exponent depends on a parameter (`" + emit::ginac_text(e) +
                                "`); the numeric evaluator needs numeric exponents");
  }
  if (is_a<function>(e)) {
    const std::string name = ex_to<function>(e).get_name();
    if (name == "sin") return emit(Op::Sin, compile(e.op(0)));
    if (name == "cos") return emit(Op::Cos, compile(e.op(0)));
    throw std::runtime_error("evaluator: unsupported function `" + name + "`");
  }
  throw std::runtime_error("evaluator: unsupported expression");
}

void ExpressionTape::evaluate(const double* params, std::vector<double>& out) const {
  std::vector<double> registers(static_cast<std::size_t>(n_registers_));
  double* r = registers.data();
  for (int i = 0; i < n_params_; ++i) r[i] = params[i];
  for (const Instruction& in : code_) {
    double& d = r[in.dst];
    switch (in.op) {
      case Op::Const: d = in.value; break;
      case Op::Add: d = r[in.a] + r[in.b]; break;
      case Op::Mul: d = r[in.a] * r[in.b]; break;
      case Op::Div: d = r[in.a] / r[in.b]; break;
      case Op::PowInt: {
        // Exponentiation by squaring, exact for the small exponents mechanics produces.
        const int n = in.exponent < 0 ? -in.exponent : in.exponent;
        double base = r[in.a], acc = 1.0;
        for (int k = n; k > 0; k >>= 1) {
          if (k & 1) acc *= base;
          base *= base;
        }
        d = in.exponent < 0 ? 1.0 / acc : acc;
        break;
      }
      case Op::PowReal: d = std::pow(r[in.a], in.value); break;
      case Op::Sqrt: d = std::sqrt(r[in.a]); break;
      case Op::Sin: d = std::sin(r[in.a]); break;
      case Op::Cos: d = std::cos(r[in.a]); break;
    }
  }
  out.resize(outputs_.size());
  for (std::size_t i = 0; i < outputs_.size(); ++i) out[i] = r[outputs_[i]];
}

}  // namespace mbgen::evaluator
