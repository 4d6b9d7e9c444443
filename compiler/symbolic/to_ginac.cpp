#include "symbolic/to_ginac.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "frontend/diagnostics.hpp"

namespace mbgen::symbolic {

namespace {

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// Splits a decimal literal into sign, all mantissa digits, the number of digits after the point, and the
// exponent. Returns false if `text` is not a decimal literal.
bool split_decimal(const std::string& text, bool& negative, std::string& digits, long& fraction_digits,
                   std::string& exponent) {
  size_t i = 0;
  negative = false;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
  digits.clear();
  fraction_digits = 0;
  bool point = false;
  for (; i < text.size(); ++i) {
    if (is_digit(text[i])) {
      digits += text[i];
      if (point) ++fraction_digits;
    } else if (text[i] == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (digits.empty()) return false;
  exponent = "0";
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    std::string e;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) e += text[i++];
    const size_t start = i;
    while (i < text.size() && is_digit(text[i])) e += text[i++];
    if (i == start) return false;
    exponent = e;
  }
  return i == text.size();
}

}  // namespace

bool is_decimal_literal(const std::string& text) {
  bool negative;
  std::string digits, exponent;
  long fraction_digits;
  return split_decimal(text, negative, digits, fraction_digits, exponent);
}

std::string decimal_limits_violation(const std::string& text) {
  bool negative;
  std::string digits, exponent;
  long fraction_digits;
  if (!split_decimal(text, negative, digits, fraction_digits, exponent)) return "it is not a decimal number";
  if (digits.size() > static_cast<std::size_t>(kMaxLiteralDigits))
    return fmt::format("it has more than {} digits", kMaxLiteralDigits);
  // Compared as text first: the exponent may have more digits than any integer type holds.
  std::string magnitude = exponent[0] == '+' || exponent[0] == '-' ? exponent.substr(1) : exponent;
  magnitude.erase(0, std::min(magnitude.find_first_not_of('0'), magnitude.size()));
  if (magnitude.size() > 6 || std::stol(magnitude.empty() ? "0" : magnitude) > kMaxDecimalExponent)
    return fmt::format("its exponent lies outside -{} to {}", kMaxDecimalExponent, kMaxDecimalExponent);
  return "";
}

GiNaC::numeric parse_decimal(const std::string& text) {
  bool negative;
  std::string digits, exponent;
  long fraction_digits;
  if (!split_decimal(text, negative, digits, fraction_digits, exponent))
    throw std::invalid_argument("not a decimal literal: `" + text + "`");
  const std::string violation = decimal_limits_violation(text);
  if (!violation.empty()) throw std::out_of_range("`" + text + "` is out of range: " + violation);
  // Integers given as digit strings are parsed exactly by CLN.
  const GiNaC::numeric mantissa(digits.c_str());
  const std::string exp_text = exponent[0] == '+' ? exponent.substr(1) : exponent;
  const GiNaC::numeric power = GiNaC::numeric(exp_text.c_str()) - GiNaC::numeric(fraction_digits);
  GiNaC::numeric value = mantissa * GiNaC::pow(GiNaC::numeric(10), power);
  return negative ? -value : value;
}

namespace {

// Bits of an exact rational: the larger of its numerator's and denominator's.
long rational_bits(const GiNaC::numeric& n) {
  return std::max(GiNaC::numer(n).int_length(), GiNaC::denom(n).int_length());
}

// The value of an exponent for a message: "7.6256e+12", or "not a real number".
std::string exponent_text(const GiNaC::ex& value) {
  if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_real()) return "not a real number";
  return fmt::format("{:g}", GiNaC::ex_to<GiNaC::numeric>(value).to_double());
}

// The most bits of any exact rational in e (coefficients, exponents, numbers under functions).
long largest_rational_bits(const GiNaC::ex& e) {
  long bits = 0;
  for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::numeric>(*it) && GiNaC::ex_to<GiNaC::numeric>(*it).is_rational())
      bits = std::max(bits, rational_bits(GiNaC::ex_to<GiNaC::numeric>(*it)));
  return bits;
}

// Why zero to the power n has no value ("" when it has one).
std::string zero_power_fault(const GiNaC::ex& n) {
  if (!GiNaC::is_a<GiNaC::numeric>(n) || GiNaC::ex_to<GiNaC::numeric>(n).is_positive()) return "";
  return n.is_zero() ? "0^0 is undefined" : "division by zero";
}

// Substitutes values bottom-up and stops at a power of zero that has no value, before GiNaC sees it: GiNaC throws
// there from inside its substitution and leaks the product it was building (found by the fuzzer under ASan).
struct SubstituteValues : GiNaC::map_function {
  const GiNaC::exmap& at;
  std::string fault;
  explicit SubstituteValues(const GiNaC::exmap& values) : at(values) {}
  GiNaC::ex operator()(const GiNaC::ex& x) override {
    if (!fault.empty()) return x;
    if (GiNaC::is_a<GiNaC::symbol>(x)) {
      const auto v = at.find(x);
      return v == at.end() ? x : v->second;
    }
    if (!GiNaC::is_a<GiNaC::power>(x)) return x.map(*this);
    const GiNaC::ex base = (*this)(x.op(0)), exponent = (*this)(x.op(1));
    if (fault.empty() && base.is_zero()) fault = zero_power_fault(exponent);
    return fault.empty() ? GiNaC::pow(base, exponent) : x;
  }
};

}  // namespace

void ParameterTable::check_power(const ir::Expr& e, const GiNaC::ex& base, const GiNaC::ex& exponent) const {
  // A power of expressions in parameters is checked at the parameters' values: wherever they are substituted, it is
  // computed exactly there (q^(q^(q^q)) with q = 3 is 3^7625597484987 and would fill the memory). Its operands'
  // own values passed this check when they were converted, so substituting into them is cheap.
  const bool at_values = !GiNaC::is_a<GiNaC::numeric>(base) || !GiNaC::is_a<GiNaC::numeric>(exponent);
  GiNaC::ex b = base, n = exponent;
  if (at_values) {
    b = value_at(e, base);
    n = value_at(e, exponent);
    // Zero to a power that is not positive has no value (q^(q-1) with q = 0).
    if (b.is_zero()) {
      const std::string fault = zero_power_fault(n);
      if (!fault.empty()) fail_without_value(e, fault);
    }
  }
  const GiNaC::ex n_value = GiNaC::is_a<GiNaC::numeric>(n) ? n : GiNaC::evalf(n);
  // A large exponent is computed exactly when the base is a number (2^(2^64) would fill the memory), and gives
  // no useful double otherwise.
  const bool exact_exponent = GiNaC::is_a<GiNaC::numeric>(exponent);
  if (!GiNaC::is_a<GiNaC::numeric>(n_value) || !GiNaC::ex_to<GiNaC::numeric>(n_value).is_real() ||
      (exact_exponent && !GiNaC::ex_to<GiNaC::numeric>(n_value).is_rational()) ||
      GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(n_value)) > kMaxExponent) {
    if (exact_exponent)
      throw frontend::ModelError(model_.file, e.loc, "`{}`: the exponent must be a number within -{} to {}",
                                 ir::to_string(e), kMaxExponent, kMaxExponent);
    throw frontend::ModelError(model_.file, e.loc,
                               "`{}`: at the parameters' values the exponent is {}; it must lie within -{} to {}",
                               ir::to_string(e), exponent_text(n_value), kMaxExponent, kMaxExponent);
  }
  // The power itself, before any value is substituted: GiNaC raises the numbers of a product to the power at once
  // ((q*10^1000)^1000 holds 10^1000000 whatever q is, and with q = 0 its value would pass the check below).
  if (exact_exponent && GiNaC::ex_to<GiNaC::numeric>(exponent).is_rational() &&
      largest_rational_bits(base) * GiNaC::abs(GiNaC::numer(GiNaC::ex_to<GiNaC::numeric>(exponent))).to_long() >
          kMaxNumberBits)
    throw frontend::ModelError(model_.file, e.loc, "`{}` is too large an exact number: {}", ir::to_string(e),
                               too_large_text());
  // A negative base to a fractional power has no real value ((0-8)^(1/3), sqrt(m-3) at m = 2): the emitted code
  // would compute NaN, and the exact stage an imaginary number.
  const GiNaC::ex b_value = GiNaC::evalf(b);
  if (GiNaC::is_a<GiNaC::numeric>(b_value)) {
    const GiNaC::numeric& bv = GiNaC::ex_to<GiNaC::numeric>(b_value);
    const GiNaC::numeric& nv = GiNaC::ex_to<GiNaC::numeric>(n_value);
    const bool whole = nv.is_integer() || (!nv.is_rational() && std::nearbyint(nv.to_double()) == nv.to_double());
    if (!bv.is_real()) fail_without_value(e, "its base is not a real number");
    if (bv.is_negative() && !whole)
      fail_without_value(e, fmt::format("a negative number ({:.6g}) to the fractional power {} has no real value",
                                        bv.to_double(),
                                        nv.is_rational() && nv.denom() < 1000000
                                            ? fmt::format("{}/{}", nv.numer().to_long(), nv.denom().to_long())
                                            : exponent_text(n_value)));
  }
  if (!GiNaC::is_a<GiNaC::numeric>(b) || !GiNaC::is_a<GiNaC::numeric>(n)) return;
  const GiNaC::numeric& bn = GiNaC::ex_to<GiNaC::numeric>(b);
  const GiNaC::numeric& nn = GiNaC::ex_to<GiNaC::numeric>(n);
  if (!bn.is_rational() || !nn.is_rational()) return;
  const long bits = rational_bits(bn) * GiNaC::abs(GiNaC::numer(nn)).to_long();
  if (bits > kMaxNumberBits)
    throw frontend::ModelError(model_.file, e.loc, "`{}` is too large an exact number{}: {}", ir::to_string(e),
                               at_values ? " at the parameters' values" : "", too_large_text());
}

void ParameterTable::check_trigonometric_argument(const ir::Expr& e, const GiNaC::ex& x) const {
  // The values are computed in double precision (GiNaC's evalf, the emitted code's std::sin), which reduce a large
  // argument modulo 2 pi differently: sin(1e30) gave a 4.32 Hz mode exactly, 3.58 Hz in the emitted code, where the
  // true value gives 3.39 Hz. An angle of a model is small; beyond kMaxTrigArgument its sine is not known.
  const GiNaC::ex value = GiNaC::evalf(GiNaC::is_a<GiNaC::numeric>(x) ? x : value_at(e, x));
  if (!GiNaC::is_a<GiNaC::numeric>(value)) return;
  const GiNaC::numeric& v = GiNaC::ex_to<GiNaC::numeric>(value);
  if (!v.is_real()) fail_without_value(e, "its argument is not a real number");
  if (std::abs(v.to_double()) > kMaxTrigArgument)
    throw frontend::ModelError(model_.file, e.loc,
                               "`{}`: the argument is {:.6g} rad; beyond {:g} rad its value is not computed "
                               "reliably in double precision (reduce the angle modulo 2 pi in the model)",
                               ir::to_string(e), v.to_double(), kMaxTrigArgument);
}

GiNaC::ex ParameterTable::value_at(const ir::Expr& e, const GiNaC::ex& x) const {
  SubstituteValues substitute(at_);
  const GiNaC::ex value = substitute(x);
  if (!substitute.fault.empty()) fail_without_value(e, substitute.fault);
  return value;
}

void ParameterTable::fail_without_value(const ir::Expr& e, const std::string& why) const {
  throw frontend::ModelError(model_.file, e.loc, "`{}` has no value at the parameters' values: {}", ir::to_string(e),
                             why);
}

GiNaC::ex ParameterTable::bounded(const ir::Expr& e, const GiNaC::ex& value) const {
  if (GiNaC::is_a<GiNaC::numeric>(value) && GiNaC::ex_to<GiNaC::numeric>(value).is_rational() &&
      rational_bits(GiNaC::ex_to<GiNaC::numeric>(value)) > kMaxNumberBits)
    throw frontend::ModelError(model_.file, e.loc, "`{}` is too large an exact number: {}", ir::to_string(e),
                               too_large_text());
  return value;
}

// Why a value or bound cannot become a double.
constexpr const char* kBeyondDoubles = "beyond the range of a double (magnitudes from about 2.2e-308 to 1.8e308, or 0)";

std::string ParameterTable::too_large_text() {
  return fmt::format("its numerator or denominator would have more than {} bits", kMaxNumberBits);
}

ParameterTable::ParameterTable(const ir::ModelIr& model, const std::map<std::string, std::string>& overrides,
                               const std::string& origin)
    : model_(model) {
  for (const auto& [name, value] : overrides) {
    const ir::Parameter* p = model.find_parameter(name);
    if (!p)
      throw frontend::ModelError(model.file, {},
                                 "{} {}={}: the model has no parameter named `{}`; only declared parameters can be "
                                 "set",
                                 origin, name, value, name);
    if (p->derived)
      throw frontend::ModelError(model.file, p->loc,
                                 "{} {}={}: `{}` is derived (= {}) and cannot be set; set the free parameters it is "
                                 "built from instead",
                                 origin, name, value, name, ir::to_string(p->value));
    if (!is_decimal_literal(value))
      throw frontend::ModelError(model.file, {},
                                 "{} {}={}: the value must be a decimal number such as 1.5, -2 or 60e6", origin,
                                 name, value);
    if (const std::string violation = decimal_limits_violation(value); !violation.empty())
      throw frontend::ModelError(model.file, {}, "{} {}={}: out of range: {}", origin, name, value,
                                 violation);
  }
  for (const ir::Parameter& p : model.parameters) {
    if (p.derived) continue;
    FreeParameter fp;
    fp.name = p.name;
    fp.sym = GiNaC::symbol(p.name);
    fp.ir = &p;
    symbol_of_[p.name] = fp.sym;
    free_.push_back(fp);
  }
  for (FreeParameter& fp : free_) {
    const auto o = overrides.find(fp.name);
    if (o != overrides.end()) {
      fp.value = parse_decimal(o->second);
      continue;
    }
    // A parameter that is not derived must not depend on others (the parser marks those derived).
    const std::vector<std::string> uses = ir::symbols_of(fp.ir->value);
    if (!uses.empty())
      throw frontend::ModelError(model.file, fp.ir->value.loc,
                                 "the value of free parameter `{}` uses parameter `{}`; a free parameter needs a "
                                 "constant value",
                                 fp.name, uses.front());
    fp.value = convert(fp.ir->value);
  }
  // One map of the values for all checks and conversions (a map per parameter made a 300-parameter model's table
  // quadratic). Until here it was empty, and needed not be: the free parameters' values are constants.
  for (const FreeParameter& fp : free_) at_[fp.sym] = fp.value;
  for (const FreeParameter& fp : free_) check_bounds(fp, overrides.count(fp.name) ? overrides.at(fp.name) : "", origin);
  // Every value, derived ones included, must be a real number at these values (sqrt(-1) as a mass is not).
  for (const ir::Parameter& p : model.parameters) {
    const GiNaC::ex v = GiNaC::evalf(value_at(p.value, convert(ir::Expr::symbol(p.name, p.value.loc))));
    if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
      throw frontend::ModelError(model.file, p.value.loc, "the value of parameter `{}` is not a real number", p.name);
  }
}

void ParameterTable::check_bounds(const FreeParameter& fp, const std::string& set_text,
                                  const std::string& origin) const {
  const ir::Parameter& p = *fp.ir;
  // Values and bounds become doubles in generated code and fits: beyond the double range they would be infinite,
  // and below its smallest normal number (about 2.2e-308) they would lose their digits or become zero (a mass of
  // 1e-400 is positive exactly and zero in the fit).
  const GiNaC::numeric largest(std::numeric_limits<double>::max()), smallest(std::numeric_limits<double>::min());
  auto beyond_doubles = [&](const GiNaC::ex& v) {
    if (!GiNaC::is_a<GiNaC::numeric>(v)) return false;
    const GiNaC::numeric magnitude = GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(v));
    return magnitude > largest || (!magnitude.is_zero() && magnitude < smallest);
  };
  const GiNaC::ex value = GiNaC::evalf(fp.value);
  if (beyond_doubles(value))
    throw frontend::ModelError(model_.file, set_text.empty() ? p.value.loc : p.loc, "{}the value of `{}` is {}",
                               set_text.empty() ? "" : fmt::format("{} {}={}: ", origin, p.name, set_text), p.name,
                               kBeyondDoubles);
  if (!p.lower && !p.upper) return;
  auto value_of = [&](const ir::Expr& bound) {
    const GiNaC::ex v = GiNaC::evalf(value_at(bound, convert(bound)));
    if (beyond_doubles(v))
      throw frontend::ModelError(model_.file, bound.loc, "the bound `{}` of `{}` is {}; write inf for an open end",
                                 ir::to_string(bound), p.name, kBeyondDoubles);
    return v;
  };
  const GiNaC::ex lower = p.lower ? value_of(*p.lower) : GiNaC::ex();
  const GiNaC::ex upper = p.upper ? value_of(*p.upper) : GiNaC::ex();
  auto below = [](const GiNaC::ex& a, const GiNaC::ex& b) {  // a < b, for numbers
    return GiNaC::is_a<GiNaC::numeric>(a) && GiNaC::is_a<GiNaC::numeric>(b) &&
           GiNaC::ex_to<GiNaC::numeric>(a) < GiNaC::ex_to<GiNaC::numeric>(b);
  };
  const std::string range = fmt::format("[{}, {}]", p.lower ? ir::to_string(*p.lower) : std::string("-inf"),
                                        p.upper ? ir::to_string(*p.upper) : std::string("inf"));
  if (p.lower && p.upper && below(upper, lower))
    throw frontend::ModelError(model_.file, p.upper->loc,
                               "parameter `{}`: the upper bound lies below the lower bound in {}", p.name, range);
  if ((p.lower && below(value, lower)) || (p.upper && below(upper, value))) {
    if (!set_text.empty())
      throw frontend::ModelError(model_.file, p.loc, "{} {}={}: outside the bounds {} declared for `{}`", origin,
                                 p.name, set_text, range, p.name);
    throw frontend::ModelError(model_.file, p.value.loc, "the value of parameter `{}` lies outside its bounds {}",
                               p.name, range);
  }
}

GiNaC::ex ParameterTable::derived_value(const ir::Parameter& p) const {
  const auto memo = derived_.find(p.name);
  if (memo != derived_.end()) return memo->second;
  const auto cycle_start = std::find(expanding_.begin(), expanding_.end(), &p);
  if (cycle_start != expanding_.end()) {
    std::string chain;
    for (auto it = cycle_start; it != expanding_.end(); ++it) chain += (*it)->name + " -> ";
    chain += p.name;
    throw frontend::ModelError(model_.file, p.loc,
                               "parameter `{}` is defined in terms of itself ({}); give one of these parameters a "
                               "numeric value",
                               p.name, chain);
  }
  expanding_.push_back(&p);
  const GiNaC::ex value = convert(p.value);
  expanding_.pop_back();
  derived_[p.name] = value;
  return value;
}

GiNaC::ex ParameterTable::convert(const ir::Expr& e) const {
  using K = ir::Expr::Kind;
  auto fail = [&](const std::string& message) -> GiNaC::ex {
    throw frontend::ModelError(model_.file, e.loc, message);
  };
  switch (e.kind) {
    case K::Number: {
      if (!is_decimal_literal(e.text) || e.text[0] == '-' || e.text[0] == '+')
        return fail(fmt::format("`{}` is not a number; write digits with an optional point and exponent, e.g. "
                                "0.127 or 60e6",
                                e.text));
      const std::string violation = decimal_limits_violation(e.text);
      if (!violation.empty()) return fail(fmt::format("number `{}` is out of range: {}", e.text, violation));
      return parse_decimal(e.text);
    }
    case K::Symbol: {
      const auto free = symbol_of_.find(e.text);
      if (free != symbol_of_.end()) return free->second;
      if (const ir::Parameter* p = model_.find_parameter(e.text)) return derived_value(*p);
      if (e.text == "pi") return GiNaC::Pi;
      return fail(fmt::format("unknown parameter `{}`: declare it with `param {} = VALUE`", e.text, e.text));
    }
    case K::Add:
    case K::Mul: {
      // One GiNaC node for all terms (factors): adding them one at a time would rebuild the sum each time. Numbers
      // are combined here, one at a time, so that an exact result growing past the limit stops the work early.
      const bool sum = e.kind == K::Add;
      GiNaC::exvector operands;
      operands.reserve(e.args.size());
      GiNaC::numeric constant = sum ? 0 : 1;
      for (const ir::Expr& a : e.args) {
        const GiNaC::ex x = convert(a);
        if (!GiNaC::is_a<GiNaC::numeric>(x)) {
          operands.push_back(x);
          continue;
        }
        constant = sum ? constant + GiNaC::ex_to<GiNaC::numeric>(x) : constant * GiNaC::ex_to<GiNaC::numeric>(x);
        bounded(e, constant);
      }
      operands.push_back(constant);
      return bounded(e, sum ? GiNaC::ex(GiNaC::add(operands)) : GiNaC::ex(GiNaC::mul(operands)));
    }
    case K::Sub: return convert(e.args.at(0)) - convert(e.args.at(1));
    case K::Div: {
      const GiNaC::ex denominator = convert(e.args.at(1));
      if (denominator.is_zero()) return fail(fmt::format("division by zero in `{}`", ir::to_string(e)));
      // At the parameters' values too: an element's `stiffness 2/q` with q = 0 would fail wherever the model is
      // evaluated, far from the text that caused it.
      if (!GiNaC::is_a<GiNaC::numeric>(denominator) && value_at(e, denominator).is_zero())
        fail_without_value(e, "division by zero");
      return bounded(e, convert(e.args.at(0)) / denominator);
    }
    case K::Pow: {
      const GiNaC::ex base = convert(e.args.at(0)), exponent = convert(e.args.at(1));
      if (base.is_zero() && !exponent.is_zero() && GiNaC::is_a<GiNaC::numeric>(exponent) &&
          !GiNaC::ex_to<GiNaC::numeric>(exponent).is_positive())
        return fail(fmt::format("`{}`: zero to a power that is not positive", ir::to_string(e)));
      if (base.is_zero() && exponent.is_zero()) return fail(fmt::format("`{}`: 0^0 is undefined", ir::to_string(e)));
      check_power(e, base, exponent);
      return bounded(e, GiNaC::pow(base, exponent));
    }
    case K::Neg: return -convert(e.args.at(0));
    case K::Call: {
      if (e.args.size() != 1)
        return fail(fmt::format("function `{}` takes one argument, got {}", e.text, e.args.size()));
      const GiNaC::ex x = convert(e.args[0]);
      if (e.text == "sqrt") {
        check_power(e, x, GiNaC::numeric(1, 2));
        return GiNaC::sqrt(x);
      }
      if (e.text == "sin" || e.text == "cos") check_trigonometric_argument(e, x);
      if (e.text == "sin") return GiNaC::sin(x);
      if (e.text == "cos") return GiNaC::cos(x);
      return fail(fmt::format("unknown function `{}`; the functions are sqrt, sin and cos", e.text));
    }
  }
  return fail("malformed expression");
}

}  // namespace mbgen::symbolic
