#include "emit/cxx_printer.hpp"

#include <sstream>
#include <algorithm>
#include <stdexcept>

#include "passes/cse.hpp"
#include "emit/ginac_text.hpp"
#include "passes/sign_free_key.hpp"

namespace mbgen::emit {
namespace {

// Printed text and its binding strength: 0 sum, 1 product/quotient/negation, 2 atom.
struct Printed {
  std::string text;
  int prec = 2;
};

bool starts_negative(const std::string& s) { return !s.empty() && s[0] == '-'; }

std::string as_factor(const Printed& p) {
  if (p.prec < 1 || starts_negative(p.text)) return "(" + p.text + ")";
  return p.text;
}

std::string as_atom(const Printed& p) { return p.prec < 2 ? "(" + p.text + ")" : p.text; }

// A non-negative integer as Scalar arithmetic that is exact wherever the Scalar type can hold the value:
// below 10^15 (< 2^53) one literal, above that Horner's scheme in base 10^15.
std::string integer_digits(const GiNaC::numeric& n) {
  std::ostringstream os;
  os << GiNaC::ex(n);
  return os.str();
}

std::string cxx_integer(const GiNaC::numeric& n) {
  static const GiNaC::numeric base("1000000000000000");  // 10^15
  if (n < base) return "Scalar(" + integer_digits(n) + ")";
  const GiNaC::numeric q = GiNaC::iquo(n, base), r = GiNaC::irem(n, base);
  return "(" + cxx_integer(q) + "*Scalar(1000000000000000) + Scalar(" + integer_digits(r) + "))";
}

Printed print_nonneg_rational(const GiNaC::numeric& n) {
  std::string p = cxx_integer(n.numer());
  if (n.is_integer()) return {p, 2};
  return {p + "/" + cxx_integer(n.denom()), 1};
}

Printed print_number(const GiNaC::numeric& n) {
  if (!n.is_rational()) {
    if (!n.is_real()) throw std::logic_error("cxx_printer: complex number " + ginac_text(n));
    // Not expected from the exact symbolic stage; printed with enough digits for long double.
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.21Lg", static_cast<long double>(n.to_double()));
    return {std::string("Scalar(") + buf + "L)", 2};
  }
  if (n.is_negative()) {
    Printed p = print_nonneg_rational(-n);
    return {"-" + p.text, 1};
  }
  return print_nonneg_rational(n);
}

class Printer {
 public:
  explicit Printer(const SymbolNames& names) : names_(names) {}

  Printed print(const GiNaC::ex& e) const {
    if (GiNaC::is_a<GiNaC::numeric>(e)) return print_number(GiNaC::ex_to<GiNaC::numeric>(e));
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      auto it = names_.find(e);
      if (it == names_.end()) throw std::logic_error("cxx_printer: no C++ name for symbol " + ginac_text(e));
      return {it->second, 2};
    }
    if (GiNaC::is_a<GiNaC::constant>(e)) {
      if (e.is_equal(GiNaC::Pi)) return {"c_pi", 2};
      throw std::logic_error("cxx_printer: unsupported constant " + ginac_text(e));
    }
    if (GiNaC::is_a<GiNaC::add>(e)) return print_add(e);
    if (GiNaC::is_a<GiNaC::mul>(e)) return print_mul(e);
    if (GiNaC::is_a<GiNaC::power>(e)) {
      const auto [magnitude, negative] = signed_factor(e);
      return negative ? Printed{"-" + magnitude.text, 1} : magnitude;
    }
    if (GiNaC::is_a<GiNaC::function>(e)) return print_function(e);
    throw std::logic_error("cxx_printer: unsupported expression " + ginac_text(e));
  }

 private:
  const SymbolNames& names_;
  mutable passes::SignFreeKeys keys_;

  static std::string negated(const std::string& term) {
    return starts_negative(term) ? term.substr(1) : "-" + term;
  }

  // Operands are printed in the order of their text, not GiNaC's internal order (which follows hash values, and so
  // differs from run to run): output is deterministic. With `negate`, every term's sign is flipped: -(a - b) is
  // written b - a.
  Printed print_add(const GiNaC::ex& e, bool negate = false) const {
    std::vector<std::string> terms;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      Printed t = print(e.op(i));
      std::string text = t.prec < 1 ? "(" + t.text + ")" : t.text;
      terms.push_back(negate ? negated(text) : text);
    }
    std::sort(terms.begin(), terms.end(), [](const std::string& x, const std::string& y) {
      if (starts_negative(x) != starts_negative(y)) return !starts_negative(x);  // a positive term first
      return x < y;
    });
    std::string s;
    for (std::size_t i = 0; i < terms.size(); ++i) {
      const std::string& text = terms[i];
      if (i == 0) {
        s = text;
      } else if (starts_negative(text)) {
        s += " - " + text.substr(1);
      } else {
        s += " + " + text;
      }
    }
    return {s, 0};
  }

  // A factor of a product as its magnitude and whether it is negative: a sum, or an integer power of one, is
  // written with the sign sign_free_key.hpp gives it (GiNaC's choice of (a - b) or -(b - a) follows hash values,
  // which differ from run to run, and the text must not).
  std::pair<Printed, bool> signed_factor(const GiNaC::ex& f) const {
    const passes::SignFreeKeys::FactorSign fs = keys_.factor_sign(f);
    if (GiNaC::is_a<GiNaC::add>(f)) return {print_add(f, fs.negate_sum), fs.negative};
    if (GiNaC::is_a<GiNaC::power>(f)) return {print_power(f, fs.negate_sum), fs.negative};
    return {print(f), false};
  }

  Printed base_of(const GiNaC::ex& f, bool flip) const { return flip ? print_add(f.op(0), true) : print(f.op(0)); }

  static bool is_negative_integer_power(const GiNaC::ex& f) {
    return GiNaC::is_a<GiNaC::power>(f) && f.op(1).info(GiNaC::info_flags::negint);
  }

  Printed print_mul(const GiNaC::ex& e) const {
    GiNaC::numeric coeff = 1;
    std::vector<std::string> num, den;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const GiNaC::ex& f = e.op(i);
      if (GiNaC::is_a<GiNaC::numeric>(f)) {
        coeff *= GiNaC::ex_to<GiNaC::numeric>(f);
      } else if (is_negative_integer_power(f)) {
        const passes::SignFreeKeys::FactorSign fs = keys_.factor_sign(f);
        if (fs.negative) coeff = -coeff;
        den.push_back(as_factor(raised(base_of(f, fs.negate_sum), -GiNaC::ex_to<GiNaC::numeric>(f.op(1)))));
      } else {
        const auto [magnitude, negative] = signed_factor(f);
        if (negative) coeff = -coeff;
        num.push_back(as_factor(magnitude));
      }
    }
    std::sort(num.begin(), num.end());
    std::sort(den.begin(), den.end());
    if (!coeff.is_rational()) {
      num.insert(num.begin(), as_factor(print_number(coeff)));
      coeff = 1;
    }
    bool negative = coeff.is_negative();
    GiNaC::numeric c = negative ? -coeff : coeff;
    std::vector<std::string> parts;
    if (!c.is_integer()) {
      parts.push_back(print_nonneg_rational(c).text);
    } else if (!c.is_equal(1) || num.empty()) {
      parts.push_back(print_nonneg_rational(c).text);
    }
    parts.insert(parts.end(), num.begin(), num.end());
    std::string s;
    for (std::size_t i = 0; i < parts.size(); ++i) s += (i ? "*" : "") + parts[i];
    if (!den.empty()) {
      std::string d;
      for (std::size_t i = 0; i < den.size(); ++i) d += (i ? "*" : "") + den[i];
      bool single_atom = den.size() == 1 && d.find_first_of("*/+- ") == std::string::npos;
      s += "/" + (single_atom ? d : "(" + d + ")");
    }
    bool atom = !negative && parts.size() == 1 && den.empty() && s.find_first_of("*/") == std::string::npos;
    return {(negative ? "-" : "") + s, atom ? 2 : 1};
  }

  // base^expo; with `negate_base` the base (a sum) is written with its terms' signs flipped.
  Printed print_power(const GiNaC::ex& e, bool negate_base = false) const {
    const GiNaC::ex& expo = e.op(1);
    const Printed base = base_of(e, negate_base);
    if (GiNaC::is_a<GiNaC::numeric>(expo)) {
      GiNaC::numeric k = GiNaC::ex_to<GiNaC::numeric>(expo);
      if (k.is_integer() && k.is_negative()) return {"Scalar(1)/" + as_atom(raised(base, -k)), 1};
      if (k.is_equal(GiNaC::numeric(1, 2))) return {"sqrt(" + base.text + ")", 2};
      if (k.is_equal(GiNaC::numeric(-1, 2))) return {"Scalar(1)/sqrt(" + base.text + ")", 1};
      return raised(base, k);
    }
    return {"pow(" + base.text + ", " + print(expo).text + ")", 2};
  }

  // base^k for a number k: x^2..x^4 as products, others by pow().
  Printed raised(const Printed& base, const GiNaC::numeric& k) const {
    if (k.is_equal(1)) return base;
    if (k.is_integer() && k >= 2 && k <= 4) {
      std::string b = as_atom(base);
      std::string s = b;
      for (int i = 1; i < k.to_int(); ++i) s += "*" + b;
      return {s, 1};
    }
    return {"pow(" + base.text + ", " + print_number(k).text + ")", 2};
  }

  Printed print_function(const GiNaC::ex& e) const {
    std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    static const char* const allowed[] = {"sin", "cos", "tan", "exp", "log", "atan", "asin", "acos",
                                          "sinh", "cosh", "tanh", "abs"};
    bool ok = false;
    for (const char* a : allowed) ok = ok || name == a;
    if (!ok) throw std::logic_error("cxx_printer: unsupported function " + name);
    std::string s = name + "(";
    for (std::size_t i = 0; i < e.nops(); ++i) s += (i ? ", " : "") + print(e.op(i)).text;
    return {s + ")", 2};
  }
};

}  // namespace

std::string cxx_number(const GiNaC::numeric& n) { return print_number(n).text; }

std::string cxx_expression(const GiNaC::ex& e, const SymbolNames& names) { return Printer(names).print(e).text; }

std::string cxx_assignments(const std::vector<CxxAssignment>& assignments, const SymbolNames& names,
                            const std::string& indent, OperationCounts* counts) {
  std::vector<GiNaC::ex> rhs;
  rhs.reserve(assignments.size());
  bool uses_pi = false;
  for (const auto& a : assignments) {
    rhs.push_back(a.rhs);
    uses_pi = uses_pi || a.rhs.has(GiNaC::Pi);
  }
  passes::CseResult cse = passes::eliminate_common_subexpressions(rhs, "t");
  SymbolNames all = names;
  for (const auto& [sym, def] : cse.temporaries) all.emplace(sym, sym.get_name());
  Printer printer(all);
  std::string out;
  if (uses_pi) out += indent + "const Scalar c_pi = Scalar(4)*atan(Scalar(1));\n";
  for (const auto& [sym, def] : cse.temporaries)
    out += indent + "const Scalar " + sym.get_name() + " = " + printer.print(def).text + ";\n";
  for (std::size_t i = 0; i < assignments.size(); ++i)
    out += indent + assignments[i].lhs + " = " + printer.print(cse.outputs[i]).text + ";\n";
  if (counts) {
    OperationCounter before, after;
    for (const auto& e : rhs) counts->before_cse += before.count(e);
    for (const auto& [sym, def] : cse.temporaries) counts->after_cse += after.count(def);
    for (const auto& e : cse.outputs) counts->after_cse += after.count(e);
  }
  return out;
}

}  // namespace mbgen::emit
