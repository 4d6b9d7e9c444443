// Numbers for the extension operators: the value of an IR expression at the model's current parameter values,
// and exact literals for the start values they write into a model.
#pragma once

#include <map>
#include <string>

#include "ir/model_ir.hpp"

namespace mbgen::diagnosis {

// Values of a model's expressions. `overrides` (e.g. fitted values) replace the values written in the model.
class ModelValues {
 public:
  ModelValues(const ir::ModelIr& model, std::map<std::string, double> overrides);

  double of(const ir::Expr& e) const;
  double of_parameter(const std::string& name) const;  // throws std::invalid_argument for an unknown name

 private:
  const ir::ModelIr& model_;
  std::map<std::string, double> overrides_;
};

// A short literal of `v` (6 significant digits) that the .mdl lexer reads, e.g. "1.5e8", "0.0768", "105.84".
// `v` must be finite and non-negative.
std::string number_literal(double v);

// `v` as an expression: a literal, negated when `v` < 0.
ir::Expr number_expr(double v);

}  // namespace mbgen::diagnosis
