// ir::Expr -> GiNaC::ex with exact numbers, free parameters as symbols and derived parameters substituted.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "ir/model.hpp"
#include "symbolic/symbolic_model.hpp"

namespace mbgen::symbolic {

// True if `text` is a decimal literal: optional sign, digits with an optional point, optional exponent.
bool is_decimal_literal(const std::string& text);
// The exact rational a decimal literal denotes ("0.127" -> 127/1000, "1.5E-3" -> 3/2000). The digits are read as
// arbitrary-precision integers, never through a double. Throws std::invalid_argument if not a decimal literal.
GiNaC::numeric parse_decimal(const std::string& text);

// The parameters of a model as GiNaC objects. Free parameters become symbols (with their exact values, after
// `--set` overrides); derived parameters are substituted by their definitions, recursively.
class ParameterTable {
 public:
  // Throws frontend::ModelError for an unknown or derived override name, a malformed override value, a cycle
  // among derived parameters, an unknown name in an expression, or a free parameter whose value is not constant.
  ParameterTable(const ir::Model& model, const std::map<std::string, std::string>& overrides = {});

  // The expression over the free-parameter symbols; throws ModelError at the offending node.
  GiNaC::ex convert(const ir::Expr& e) const;

  const std::vector<FreeParameter>& free_parameters() const { return free_; }
  const ir::Model& model() const { return model_; }
  GiNaC::exmap values() const;  // free symbol -> exact value

 private:
  GiNaC::ex derived_value(const ir::Parameter& p) const;

  const ir::Model& model_;
  std::vector<FreeParameter> free_;
  std::map<std::string, GiNaC::ex> symbol_of_;  // free parameter name -> symbol
  mutable std::map<std::string, GiNaC::ex> derived_;  // derived parameter name -> expression (memo)
  mutable std::vector<const ir::Parameter*> expanding_;  // derived parameters being expanded (cycle check)
};

}  // namespace mbgen::symbolic
