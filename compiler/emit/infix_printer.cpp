#include "emit/infix_printer.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "emit/ginac_text.hpp"
#include "passes/sign_free_key.hpp"

namespace mbgen::emit {
namespace {

// Binding strength: 0 sum, 1 product/quotient/negation, 2 power, 3 atom.
struct Printed {
  std::string text;
  int prec = 3;
};

std::string integer_text(const GiNaC::numeric& n) {
  std::ostringstream os;
  os << GiNaC::ex(n);
  return os.str();
}

// An exact rational: a float (not expected from the exact symbolic stage) is converted to the rational it
// represents exactly, so the syntax stays integers and ratios.
GiNaC::numeric exact(const GiNaC::numeric& n) {
  if (n.is_rational()) return n;
  if (!n.is_real()) throw std::logic_error("infix_text: complex number " + ginac_text(n));
  // A double's binary value, exactly: mantissa * 2^exponent.
  int exponent = 0;
  const double mantissa = std::frexp(n.to_double(), &exponent);
  const GiNaC::numeric m(static_cast<long>(std::ldexp(mantissa, 53)));
  return m * GiNaC::pow(GiNaC::numeric(2), GiNaC::numeric(exponent - 53));
}

Printed number(const GiNaC::numeric& raw, bool latex) {
  GiNaC::numeric n = exact(raw);
  if (n.is_negative()) return {"-" + number(-n, latex).text, 1};
  if (n.is_integer()) return {integer_text(n), 3};
  if (latex) return {"\\frac{" + integer_text(n.numer()) + "}{" + integer_text(n.denom()) + "}", 3};
  return {integer_text(n.numer()) + "/" + integer_text(n.denom()), 1};
}

// A parameter's name in LaTeX math: what follows its first `_` is a subscript set upright, with every further `_`
// escaped (`m_a_b` is m subscript "a_b"; GiNaC printed `m_a_b`, a double subscript that LaTeX rejects).
std::string latex_name(const std::string& name) {
  const auto escaped = [](const std::string& s) {
    std::string out;
    for (char c : s) out += c == '_' ? std::string("\\_") : std::string(1, c);
    return out;
  };
  const std::size_t u = name.find('_');
  if (u == std::string::npos) return name.size() == 1 ? name : "\\mathit{" + name + "}";
  if (u == 0) return "\\mathit{" + escaped(name) + "}";
  const std::string head = name.substr(0, u), tail = name.substr(u + 1);
  return (head.size() == 1 ? head : "\\mathit{" + head + "}") + "_{\\mathrm{" + escaped(tail) + "}}";
}

class Printer {
 public:
  explicit Printer(bool latex = false) : latex_(latex) {}

  Printed print(const GiNaC::ex& e) const {
    if (GiNaC::is_a<GiNaC::numeric>(e)) return number(GiNaC::ex_to<GiNaC::numeric>(e), latex_);
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      const std::string& name = GiNaC::ex_to<GiNaC::symbol>(e).get_name();
      return {latex_ ? latex_name(name) : name, 3};
    }
    if (GiNaC::is_a<GiNaC::constant>(e)) {
      if (e.is_equal(GiNaC::Pi)) return {latex_ ? "\\pi" : "pi", 3};
      throw std::logic_error("infix_text: unsupported constant " + ginac_text(e));
    }
    if (GiNaC::is_a<GiNaC::add>(e)) return add(e);
    if (GiNaC::is_a<GiNaC::mul>(e)) return mul(e);
    if (GiNaC::is_a<GiNaC::power>(e)) {
      const auto [magnitude, negative] = signed_factor(e);
      return negative ? Printed{"-" + magnitude.text, 1} : magnitude;
    }
    if (GiNaC::is_a<GiNaC::function>(e)) {
      const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
      std::string s = latex_ ? "\\" + name + "\\left(" : name + "(";
      for (std::size_t i = 0; i < e.nops(); ++i) s += (i ? ", " : "") + print(e.op(i)).text;
      return {s + (latex_ ? "\\right)" : ")"), 3};
    }
    throw std::logic_error("infix_text: unsupported expression " + ginac_text(e));
  }

 private:
  std::string wrap(const Printed& p, int min_prec) const {
    if (p.prec >= min_prec) return p.text;
    return latex_ ? "\\left(" + p.text + "\\right)" : "(" + p.text + ")";
  }

  static std::string negated(const std::string& term) { return term[0] == '-' ? term.substr(1) : "-" + term; }

  // Operands in the order of their text (GiNaC's order follows hash values): deterministic output. With `negate`,
  // every term's sign is flipped: -(a - b) is written b - a.
  Printed add(const GiNaC::ex& e, bool negate = false) const {
    std::vector<std::string> terms;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      std::string t = wrap(print(e.op(i)), 1);
      terms.push_back(negate ? negated(t) : t);
    }
    std::sort(terms.begin(), terms.end(), [](const std::string& x, const std::string& y) {
      if ((x[0] == '-') != (y[0] == '-')) return y[0] == '-';  // a positive term first
      return x < y;
    });
    std::string s;
    for (std::size_t i = 0; i < terms.size(); ++i) {
      const std::string& t = terms[i];
      if (i == 0)
        s = t;
      else if (t[0] == '-')
        s += " - " + t.substr(1);
      else
        s += " + " + t;
    }
    return {s, 0};
  }

  // A factor of a product as its magnitude and whether it is negative: a sum, or an integer power of one, is
  // written with the sign sign_free_key.hpp gives it (GiNaC's choice of (a - b) or -(b - a) follows hash values,
  // which differ from run to run, and the text must not).
  std::pair<Printed, bool> signed_factor(const GiNaC::ex& f) const {
    const passes::SignFreeKeys::FactorSign fs = keys_.factor_sign(f);
    if (GiNaC::is_a<GiNaC::add>(f)) return {add(f, fs.negate_sum), fs.negative};
    if (GiNaC::is_a<GiNaC::power>(f)) return {power(f, fs.negate_sum), fs.negative};
    return {print(f), false};
  }

  Printed base_of(const GiNaC::ex& f, bool flip) const { return flip ? add(f.op(0), true) : print(f.op(0)); }

  Printed mul(const GiNaC::ex& e) const {
    GiNaC::numeric coeff = 1;
    std::vector<std::string> num, den;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const GiNaC::ex& f = e.op(i);
      if (GiNaC::is_a<GiNaC::numeric>(f)) {
        coeff *= exact(GiNaC::ex_to<GiNaC::numeric>(f));
      } else if (GiNaC::is_a<GiNaC::power>(f) && f.op(1).info(GiNaC::info_flags::negative) &&
                 GiNaC::is_a<GiNaC::numeric>(f.op(1))) {
        const passes::SignFreeKeys::FactorSign fs = keys_.factor_sign(f);
        if (fs.negative) coeff = -coeff;
        den.push_back(wrap(raised(base_of(f, fs.negate_sum), -f.op(1)), 2));
      } else {
        const auto [magnitude, negative] = signed_factor(f);
        if (negative) coeff = -coeff;
        num.push_back(wrap(magnitude, 2));
      }
    }
    std::sort(num.begin(), num.end());
    std::sort(den.begin(), den.end());
    const bool negative = coeff.is_negative();
    if (negative) coeff = -coeff;
    if (!coeff.numer().is_equal(1) || num.empty()) num.insert(num.begin(), integer_text(coeff.numer()));
    if (!coeff.denom().is_equal(1)) den.insert(den.begin(), integer_text(coeff.denom()));
    const std::string times = latex_ ? " " : "*";
    std::string s;
    for (std::size_t i = 0; i < num.size(); ++i) s += (i ? times : "") + num[i];
    if (!den.empty()) {
      std::string d;
      for (std::size_t i = 0; i < den.size(); ++i) d += (i ? times : "") + den[i];
      if (latex_) return {(negative ? "-" : "") + std::string("\\frac{") + s + "}{" + d + "}", negative ? 1 : 3};
      s += "/" + (den.size() == 1 ? d : "(" + d + ")");
    }
    const bool single = !negative && num.size() == 1 && den.empty();
    return {(negative ? "-" : "") + s, single ? 2 : 1};
  }

  // base^expo; with `negate_base` the base (a sum) is written with its terms' signs flipped.
  Printed power(const GiNaC::ex& e, bool negate_base = false) const {
    const GiNaC::ex& expo = e.op(1);
    const Printed b = base_of(e, negate_base);
    if (GiNaC::is_a<GiNaC::numeric>(expo) && expo.info(GiNaC::info_flags::negative)) {
      if (latex_) return {"\\frac{1}{" + raised(b, -expo).text + "}", 3};
      return {"1/" + wrap(raised(b, -expo), 2), 1};
    }
    return raised(b, expo);
  }

  Printed raised(const Printed& base, const GiNaC::ex& expo) const {
    if (expo.is_equal(1)) return base;
    if (!latex_) return {wrap(base, 3) + "^" + wrap(print(expo), 3), 2};
    if (expo.is_equal(GiNaC::numeric(1, 2))) return {"\\sqrt{" + base.text + "}", 3};
    return {wrap(base, 3) + "^{" + print(expo).text + "}", 2};
  }

  bool latex_;
  mutable passes::SignFreeKeys keys_;
};

}  // namespace

std::string infix_text(const GiNaC::ex& e) { return Printer().print(e).text; }

std::string latex_text(const GiNaC::ex& e) { return Printer(true).print(e).text; }

}  // namespace mbgen::emit
