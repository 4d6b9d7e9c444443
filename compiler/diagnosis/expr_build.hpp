// Building IR expressions that read as a person would write them: literal zeros and ones are folded away
// (m + 0 -> m, 1*x -> x, 0*x -> 0), nothing else is simplified.
#pragma once

#include <string>

#include "ir/model_ir.hpp"

namespace mbgen::diagnosis {

bool is_zero_literal(const ir::Expr& e);
bool is_one_literal(const ir::Expr& e);
bool same_expr(const ir::Expr& a, const ir::Expr& b);  // the same tree (compared as text)

ir::Expr sym(const std::string& name);
ir::Expr num(const std::string& literal);
ir::Expr add(ir::Expr a, ir::Expr b);
ir::Expr sub(ir::Expr a, ir::Expr b);
ir::Expr mul(ir::Expr a, ir::Expr b);
ir::Expr div(ir::Expr a, ir::Expr b);
ir::Expr square(ir::Expr a);
ir::Expr neg(ir::Expr a);

// `e` with every derived parameter replaced by its definition, recursively: two inertias written through
// different names for one quantity (J_syy = J_sxx) compare equal after this.
ir::Expr expand_derived(const ir::ModelIr& model, const ir::Expr& e);

}  // namespace mbgen::diagnosis
