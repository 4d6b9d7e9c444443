#include "ir/model_ir.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

namespace mbgen::ir {

double literal_value(const std::string& literal) {
  double value = 0;
  const char* end = literal.data() + literal.size();
  const auto [ptr, ec] = std::from_chars(literal.data(), end, value);  // locale independent, unlike strtod
  if (ec == std::errc::result_out_of_range) {
    // Too large or too small for a double: which one, from the exponent's sign.
    const std::size_t e = literal.find_first_of("eE");
    const bool tiny = e != std::string::npos && e + 1 < literal.size() && literal[e + 1] == '-';
    return tiny ? 0.0 : std::numeric_limits<double>::infinity();
  }
  if (ec != std::errc() || ptr != end) return std::numeric_limits<double>::quiet_NaN();
  return value;
}

bool is_zero_literal(const std::string& literal) {
  for (char c : literal) {
    if (c == 'e' || c == 'E') break;
    if (std::isdigit(static_cast<unsigned char>(c)) && c != '0') return false;
  }
  return true;
}

Expr Expr::number(std::string literal, SourceLoc l) {
  Expr e;
  e.kind = Kind::Number;
  e.text = std::move(literal);
  e.loc = l;
  return e;
}

Expr Expr::symbol(std::string name, SourceLoc l) {
  Expr e;
  e.kind = Kind::Symbol;
  e.text = std::move(name);
  e.loc = l;
  return e;
}

Expr Expr::binary(Kind k, Expr a, Expr b, SourceLoc l) {
  Expr e;
  e.kind = k;
  e.args = {std::move(a), std::move(b)};
  e.loc = l;
  return e;
}

Expr Expr::sum(std::vector<Expr> terms, SourceLoc l) {
  Expr e;
  e.kind = Kind::Add;
  e.args = std::move(terms);
  e.loc = l;
  return e;
}

Expr Expr::product(std::vector<Expr> factors, SourceLoc l) {
  Expr e;
  e.kind = Kind::Mul;
  e.args = std::move(factors);
  e.loc = l;
  return e;
}

Expr Expr::negate(Expr a, SourceLoc l) {
  Expr e;
  e.kind = Kind::Neg;
  e.args = {std::move(a)};
  e.loc = l;
  return e;
}

Expr Expr::call(std::string fn, std::vector<Expr> a, SourceLoc l) {
  Expr e;
  e.kind = Kind::Call;
  e.text = std::move(fn);
  e.args = std::move(a);
  e.loc = l;
  return e;
}

namespace {

// Binding strength, matching the grammar in docs/language.md.
int precedence(const Expr& e) {
  switch (e.kind) {
    case Expr::Kind::Add:
    case Expr::Kind::Sub: return 1;
    case Expr::Kind::Mul:
    case Expr::Kind::Div: return 2;
    case Expr::Kind::Neg: return 3;
    case Expr::Kind::Pow: return 4;
    default: return 5;
  }
}

void print(const Expr& e, std::string& out);

void print_child(const Expr& e, bool parenthesize, std::string& out) {
  if (parenthesize) out += '(';
  print(e, out);
  if (parenthesize) out += ')';
}

void print(const Expr& e, std::string& out) {
  using K = Expr::Kind;
  switch (e.kind) {
    case K::Number:
    case K::Symbol: out += e.text; return;
    case K::Call:
      out += e.text;
      out += '(';
      for (std::size_t i = 0; i < e.args.size(); ++i) {
        if (i) out += ", ";
        print(e.args[i], out);
      }
      out += ')';
      return;
    case K::Neg:
      out += '-';
      // `-a^2` is -(a^2); anything weaker than a power needs parentheses.
      print_child(e.args[0], precedence(e.args[0]) < 4, out);
      return;
    case K::Pow:
      // Right associative: the base must be an atom, the exponent may be a power or a negation.
      print_child(e.args[0], precedence(e.args[0]) < 5, out);
      out += '^';
      print_child(e.args[1], precedence(e.args[1]) < 3, out);
      return;
    case K::Add:
      // A term that is itself a sum is parenthesized (it re-parses as one node); a negated term is written `- x`.
      for (std::size_t i = 0; i < e.args.size(); ++i) {
        const Expr& t = e.args[i];
        if (i > 0 && t.kind == K::Neg) {
          out += " - ";
          print_child(t.args[0], precedence(t.args[0]) <= 1, out);
          continue;
        }
        if (i > 0) out += " + ";
        print_child(t, precedence(t) <= 1, out);
      }
      return;
    case K::Mul:
      // The first factor may be a quotient (a/b*c reads ((a/b)*c)); the others must bind tighter.
      for (std::size_t i = 0; i < e.args.size(); ++i) {
        const Expr& f = e.args[i];
        if (i > 0) out += '*';
        print_child(f, i == 0 ? precedence(f) < 2 || f.kind == K::Mul : precedence(f) <= 2, out);
      }
      return;
    default: break;
  }
  // Left-associative binary operators: the right operand must bind strictly tighter to keep the tree.
  const int p = precedence(e);
  const char* op = e.kind == K::Sub ? " - " : "/";
  print_child(e.args[0], precedence(e.args[0]) < p, out);
  out += op;
  print_child(e.args[1], precedence(e.args[1]) <= p, out);
}

void collect_symbols(const Expr& e, std::vector<std::string>& out) {
  if (e.kind == Expr::Kind::Symbol) {
    if (e.text != "pi" && std::find(out.begin(), out.end(), e.text) == out.end()) out.push_back(e.text);
    return;
  }
  for (const Expr& a : e.args) collect_symbols(a, out);
}

template <typename T>
const T* find_named(const std::vector<T>& items, const std::string& name) {
  for (const T& item : items)
    if (item.name == name) return &item;
  return nullptr;
}

}  // namespace

std::string to_string(const Expr& e) {
  std::string out;
  print(e, out);
  return out;
}

std::vector<std::string> symbols_of(const Expr& e) {
  std::vector<std::string> out;
  collect_symbols(e, out);
  return out;
}

const char* to_string(Role r) {
  switch (r) {
    case Role::Known: return "known";
    case Role::Estimate: return "estimate";
    case Role::Fixed: return "fixed";
  }
  return "?";
}

const char* to_string(Dof d) {
  static const char* names[] = {"x", "y", "z", "rx", "ry", "rz"};
  return names[static_cast<int>(d)];
}

const char* to_string(ElementKind k) {
  switch (k) {
    case ElementKind::Spring: return "spring";
    case ElementKind::Spring3: return "spring3";
    case ElementKind::Torsion: return "torsion";
  }
  return "?";
}

const char* to_string(FilterKind k) {
  switch (k) {
    case FilterKind::Lowpass2: return "lowpass2";
    case FilterKind::Highpass1: return "highpass1";
    case FilterKind::Highpass2: return "highpass2";
    case FilterKind::Delay: return "delay";
    case FilterKind::Gain: return "gain";
  }
  return "?";
}

const char* to_string(InputKind k) { return k == InputKind::Force ? "force" : "moment"; }

const char* to_string(OutputKind k) {
  switch (k) {
    case OutputKind::Displacement: return "displacement";
    case OutputKind::Velocity: return "velocity";
    case OutputKind::Acceleration: return "acceleration";
  }
  return "?";
}

const Parameter* ModelIr::find_parameter(const std::string& n) const { return find_named(parameters, n); }
const Body* ModelIr::find_body(const std::string& n) const { return find_named(bodies, n); }
const Ground* ModelIr::find_ground(const std::string& n) const { return find_named(grounds, n); }

}  // namespace mbgen::ir
