#include "diagnosis/expr_build.hpp"

namespace mbgen::diagnosis {

using K = ir::Expr::Kind;

bool is_zero_literal(const ir::Expr& e) {
  if (e.kind == K::Neg) return is_zero_literal(e.args[0]);
  return e.is_number() && ir::is_zero_literal(e.text);
}

bool is_one_literal(const ir::Expr& e) { return e.is_number() && ir::literal_value(e.text) == 1.0; }

bool same_expr(const ir::Expr& a, const ir::Expr& b) { return ir::to_string(a) == ir::to_string(b); }

ir::Expr sym(const std::string& name) { return ir::Expr::symbol(name); }
ir::Expr num(const std::string& literal) { return ir::Expr::number(literal); }

ir::Expr add(ir::Expr a, ir::Expr b) {
  if (is_zero_literal(a)) return b;
  if (is_zero_literal(b)) return a;
  return ir::Expr::binary(K::Add, std::move(a), std::move(b));
}

ir::Expr sub(ir::Expr a, ir::Expr b) {
  if (is_zero_literal(b)) return a;
  if (is_zero_literal(a)) return neg(std::move(b));
  return ir::Expr::binary(K::Sub, std::move(a), std::move(b));
}

ir::Expr mul(ir::Expr a, ir::Expr b) {
  if (is_zero_literal(a) || is_zero_literal(b)) return num("0");
  if (is_one_literal(a)) return b;
  if (is_one_literal(b)) return a;
  return ir::Expr::binary(K::Mul, std::move(a), std::move(b));
}

ir::Expr div(ir::Expr a, ir::Expr b) {
  if (is_zero_literal(a)) return num("0");
  if (is_one_literal(b)) return a;
  return ir::Expr::binary(K::Div, std::move(a), std::move(b));
}

ir::Expr square(ir::Expr a) {
  if (is_zero_literal(a)) return num("0");
  return ir::Expr::binary(K::Pow, std::move(a), num("2"));
}

ir::Expr neg(ir::Expr a) {
  if (is_zero_literal(a)) return num("0");
  if (a.kind == K::Neg) return a.args[0];
  return ir::Expr::negate(std::move(a));
}

ir::Expr expand_derived(const ir::ModelIr& model, const ir::Expr& e) {
  if (e.kind == K::Symbol) {
    const ir::Parameter* p = model.find_parameter(e.text);
    if (p && p->derived) return expand_derived(model, p->value);
    return e;
  }
  ir::Expr out = e;
  for (ir::Expr& a : out.args) a = expand_derived(model, a);
  return out;
}

}  // namespace mbgen::diagnosis
