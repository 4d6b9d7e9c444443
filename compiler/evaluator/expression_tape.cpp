#include "evaluator/expression_tape.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "emit/cse.hpp"

namespace mbgen::evaluator {

ExpressionTape::ExpressionTape(const std::vector<GiNaC::symbol>& parameters, const std::vector<GiNaC::ex>& expressions) {
  n_params_ = static_cast<int>(parameters.size());
  n_registers_ = n_params_;
  for (int i = 0; i < n_params_; ++i) {
    const GiNaC::symbol& p = parameters[static_cast<std::size_t>(i)];
    registers_.emplace(p, i);
    keys_.emplace(p, p.get_name());
  }
  const emit::CseResult cse = emit::eliminate_common_subexpressions(expressions, "tape_t");
  for (const auto& [sym, body] : cse.temporaries) {
    registers_.emplace(sym, compile(body));
    keys_.emplace(sym, ordering_key(body));
  }
  for (const GiNaC::ex& e : cse.outputs) outputs_.push_back(compile(e));
  // Only needed while compiling; the tape itself holds no GiNaC object.
  registers_.clear();
  keys_.clear();
}

namespace {

// A number's magnitude as exact text (GiNaC prints rationals exactly).
std::string magnitude_text(const GiNaC::numeric& n) {
  std::ostringstream text;
  text << GiNaC::abs(n);
  return text.str();
}

// A term's numeric coefficient and what it multiplies.
std::pair<GiNaC::numeric, GiNaC::ex> split_coefficient(const GiNaC::ex& term) {
  using namespace GiNaC;
  if (is_a<numeric>(term)) return {ex_to<numeric>(term), 1};
  if (!is_a<mul>(term)) return {1, term};
  numeric c = 1;
  ex rest = 1;
  for (std::size_t i = 0; i < term.nops(); ++i) {
    if (is_a<numeric>(term.op(i)))
      c *= ex_to<numeric>(term.op(i));
    else
      rest *= term.op(i);
  }
  return {c, rest};
}

}  // namespace

const std::string& ExpressionTape::ordering_key(const GiNaC::ex& e) {
  using namespace GiNaC;
  if (auto it = keys_.find(e); it != keys_.end()) return it->second;
  std::string key;
  if (is_a<numeric>(e)) {
    key = magnitude_text(ex_to<numeric>(e));
  } else if (is_a<symbol>(e)) {
    key = ex_to<symbol>(e).get_name();
  } else if (is_a<constant>(e)) {
    std::ostringstream text;
    text << e;
    key = text.str();
  } else if (is_a<add>(e)) {
    // Terms as (what the coefficient multiplies, |coefficient|, sign), sorted; signs relative to the first term's.
    std::vector<std::pair<std::string, bool>> terms;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const auto [c, rest] = split_coefficient(e.op(i));
      terms.emplace_back(ordering_key(rest) + "*" + magnitude_text(c), c.is_negative());
    }
    std::sort(terms.begin(), terms.end());
    key = "+(";
    for (const auto& [text, negative] : terms) key += (negative == terms.front().second ? "+" : "-") + text + ",";
    key += ")";
  } else if (is_a<mul>(e)) {
    std::vector<std::string> factors;
    for (std::size_t i = 0; i < e.nops(); ++i) factors.push_back(ordering_key(e.op(i)));
    std::sort(factors.begin(), factors.end());
    key = "*(";
    for (const std::string& f : factors) key += f + ",";
    key += ")";
  } else {
    // A power or a function: operands in their fixed order. (An exponent's sign matters and is kept: exponents
    // are plain numbers GiNaC does not re-sign.)
    std::ostringstream head;
    if (is_a<power>(e))
      head << "^";
    else if (is_a<function>(e))
      head << ex_to<function>(e).get_name();
    else
      head << "?";
    key = head.str() + "(";
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex& o = e.op(i);
      key += (is_a<power>(e) && i == 1 && is_a<numeric>(o) ? std::string(ex_to<numeric>(o).is_negative() ? "-" : "")
                                                           : std::string()) +
             ordering_key(o) + ",";
    }
    key += ")";
  }
  return keys_.emplace(e, std::move(key)).first->second;
}

std::vector<GiNaC::ex> ExpressionTape::canonical_operands(const GiNaC::ex& e) {
  std::vector<std::pair<std::string, GiNaC::ex>> keyed;
  for (std::size_t i = 0; i < e.nops(); ++i) keyed.emplace_back(ordering_key(e.op(i)), e.op(i));
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<GiNaC::ex> out;
  for (auto& k : keyed) out.push_back(std::move(k.second));
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
    throw std::runtime_error("evaluator: symbolic exponents are not supported");
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
