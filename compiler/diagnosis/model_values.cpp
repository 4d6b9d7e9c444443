#include "diagnosis/model_values.hpp"
#include "numerics/constants.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mbgen::diagnosis {

ModelValues::ModelValues(const ir::ModelIr& model, std::map<std::string, double> overrides)
    : model_(model), overrides_(std::move(overrides)) {}

double ModelValues::of_parameter(const std::string& name) const {
  if (const auto it = overrides_.find(name); it != overrides_.end()) return it->second;
  const ir::Parameter* p = model_.find_parameter(name);
  if (!p) throw std::invalid_argument("no parameter `" + name + "` in model `" + model_.name + "`");
  return of(p->value);  // the front end has ruled out cycles
}

double ModelValues::of(const ir::Expr& e) const {
  using K = ir::Expr::Kind;
  switch (e.kind) {
    case K::Number: return ir::literal_value(e.text);
    case K::Symbol: return e.text == "pi" ? numerics::kPi : of_parameter(e.text);
    case K::Add: {
      double sum = 0;
      for (const ir::Expr& term : e.args) sum += of(term);
      return sum;
    }
    case K::Sub: return of(e.args[0]) - of(e.args[1]);
    case K::Mul: {
      double product = 1;
      for (const ir::Expr& factor : e.args) product *= of(factor);
      return product;
    }
    case K::Div: return of(e.args[0]) / of(e.args[1]);
    case K::Pow: return std::pow(of(e.args[0]), of(e.args[1]));
    case K::Neg: return -of(e.args[0]);
    case K::Call:
      if (e.text == "sqrt") return std::sqrt(of(e.args[0]));
      if (e.text == "sin") return std::sin(of(e.args[0]));
      if (e.text == "cos") return std::cos(of(e.args[0]));
      break;
  }
  throw std::invalid_argument("cannot evaluate `" + ir::to_string(e) + "`");
}

std::string number_literal(double v) {
  if (!std::isfinite(v) || v < 0) throw std::invalid_argument("number_literal: not a finite non-negative number");
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  std::string s = buf;
  const std::size_t e = s.find('e');
  if (e == std::string::npos) return s;
  // printf writes "1.5e+08"; the model language reads "1.5e8" (no `+`, no leading zeros).
  return s.substr(0, e) + "e" + std::to_string(std::stoi(s.substr(e + 1)));
}

ir::Expr number_expr(double v) {
  return v < 0 ? ir::Expr::negate(ir::Expr::number(number_literal(-v))) : ir::Expr::number(number_literal(v));
}

}  // namespace mbgen::diagnosis
