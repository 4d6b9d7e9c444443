// Keys and signs of GiNaC expressions that are the same in every run of the program.
//
// GiNaC keeps the operands of a sum or product in the order of their hash values, and gives a sum that is a
// factor of a product (or the base of an integer power) the sign that makes its first term in that order
// positive. Hash values follow the addresses the program is loaded at, so one run holds (a - b)*c and the next
// -(b - a)*c. Whatever orders operands or names temporaries by GiNaC's order or by a text that contains those signs
// (the common-subexpression pass, the printers, the evaluator's tape) then differs from run to run.
//
// SignFreeKeys gives each expression e
//   - a key built from its structure alone, equal for e and -e and for nothing else (numbers by magnitude, a sum by
//     its terms with signs relative to its first in key order, a product by its factors' keys without the unit
//     factor -1);
//   - a sign, so that e = sign(e)*|e| where |e|, the magnitude, is the same expression in every run: the sign of a
//     sum is that of its first term in key order, that of a product the product of its factors' signs, that of an
//     integer power its base's sign to that power.
// A base under a fractional power and a function's argument keep their sign (sqrt(a - b) is not ±sqrt(b - a)),
// so that sign is part of the key there.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mbgen::passes {

class SignFreeKeys {
 public:
  const std::string& key(const GiNaC::ex& e) { return entry(e).first; }
  int sign(const GiNaC::ex& e) { return entry(e).second; }
  // The indices of e's operands in the order of their keys (a stable sort: equal keys keep GiNaC's order).
  std::vector<std::size_t> operand_order(const GiNaC::ex& e);
  // How a printer writes a factor f of a product so that its text is the same in every run: a sum, or the base of
  // an integer power of one, with every term's sign flipped (negate_sum) when its sign is negative; f is then
  // negative (its sign goes to the product's coefficient) unless the power is even.
  struct FactorSign {
    bool negate_sum = false;
    bool negative = false;
  };
  FactorSign factor_sign(const GiNaC::ex& f);

 private:
  const std::pair<std::string, int>& entry(const GiNaC::ex& e);
  std::pair<std::string, int> compute(const GiNaC::ex& e);
  std::string signed_key(const GiNaC::ex& e);

  std::map<GiNaC::ex, std::pair<std::string, int>, GiNaC::ex_is_less> memo_;
};

// A product of a unit (±1) and a single other factor, e.g. -x, stands for that factor with a sign: GiNaC writes
// a term x of one run as -(-x) = (-1)*y in another. Returns the factor and the sign (e itself and +1 otherwise).
std::pair<GiNaC::ex, int> strip_unit_factor(const GiNaC::ex& e);

}  // namespace mbgen::passes
