// ir::Expr -> GiNaC::ex with exact numbers, free parameters as symbols and derived parameters substituted.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "ir/model_ir.hpp"
#include "symbolic/symbolic_model.hpp"

namespace mbgen::symbolic {

// Limits on exact numbers, so that no input can make the exact arithmetic grow without bound (docs/limits.md):
// a literal's digits and exponent, a numeric exponent of `^`, and the size of an exact rational in an expression.
inline constexpr int kMaxLiteralDigits = 1000;
inline constexpr long kMaxDecimalExponent = 1000;
inline constexpr long kMaxExponent = 1000;
inline constexpr long kMaxNumberBits = 100000;

// True if `text` is a decimal literal: optional sign, digits with an optional point, optional exponent.
bool is_decimal_literal(const std::string& text);
// The exact rational a decimal literal denotes ("0.127" -> 127/1000, "1.5E-3" -> 3/2000). The digits are read as
// arbitrary-precision integers, never through a double. Throws std::invalid_argument if not a decimal literal,
// std::out_of_range beyond the limits above.
GiNaC::numeric parse_decimal(const std::string& text);
// Why a decimal literal lies beyond the limits above ("it has more than 1000 digits"), or "" when it does not.
std::string decimal_limits_violation(const std::string& text);

// The parameters of a model as GiNaC objects. Free parameters become symbols (with their exact values, after
// `--set` overrides); derived parameters are substituted by their definitions, recursively.
class ParameterTable {
 public:
  // Throws frontend::ModelError for an unknown or derived override name, a malformed override value, a cycle
  // among derived parameters, an unknown name in an expression, or a free parameter whose value is not constant.
  // `origin` names where the overrides come from in the messages ("--set m1=0: ..."; "# set" for a data file's).
  ParameterTable(const ir::ModelIr& model, const std::map<std::string, std::string>& overrides = {},
                 const std::string& origin = "--set");

  // The expression over the free-parameter symbols; throws ModelError at the offending node.
  GiNaC::ex convert(const ir::Expr& e) const;

  const std::vector<FreeParameter>& free_parameters() const { return free_; }
  const ir::ModelIr& model() const { return model_; }
  const GiNaC::exmap& values() const { return at_; }  // free symbol -> exact value

 private:
  GiNaC::ex derived_value(const ir::Parameter& p) const;
  // Throws ModelError when a free parameter's value (`set_text`: as given by `origin`, else empty) lies outside its
  // declared bounds, or the bounds are reversed.
  void check_bounds(const FreeParameter& fp, const std::string& set_text, const std::string& origin) const;
  // Throw ModelError at `e` when a power or an exact number exceeds the limits above.
  void check_power(const ir::Expr& e, const GiNaC::ex& base, const GiNaC::ex& exponent) const;
  GiNaC::ex bounded(const ir::Expr& e, const GiNaC::ex& value) const;
  // x at the parameters' values; throws ModelError at `e` when it has none (a division by zero, 0^0).
  GiNaC::ex value_at(const ir::Expr& e, const GiNaC::ex& x) const;
  // sin and cos of an argument whose magnitude at the parameters' values is beyond kMaxTrigArgument: a ModelError.
  void check_trigonometric_argument(const ir::Expr& e, const GiNaC::ex& x) const;
  static constexpr double kMaxTrigArgument = 1e6;
  [[noreturn]] void fail_without_value(const ir::Expr& e, const std::string& why) const;
  static std::string too_large_text();

  const ir::ModelIr& model_;
  std::vector<FreeParameter> free_;
  std::map<std::string, GiNaC::ex> symbol_of_;  // free parameter name -> symbol
  GiNaC::exmap at_;  // free symbol -> exact value, filled once all are known
  mutable std::map<std::string, GiNaC::ex> derived_;  // derived parameter name -> expression (memo)
  mutable std::vector<const ir::Parameter*> expanding_;  // derived parameters being expanded (cycle check)
};

}  // namespace mbgen::symbolic
