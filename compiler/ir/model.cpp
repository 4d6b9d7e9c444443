#include "ir/model.hpp"

#include <algorithm>

namespace mbgen::ir {

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
    default: break;
  }
  // Left-associative binary operators: the right operand must bind strictly tighter to keep the tree.
  const int p = precedence(e);
  const char* op = e.kind == K::Add ? " + " : e.kind == K::Sub ? " - " : e.kind == K::Mul ? "*" : "/";
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

const Parameter* Model::find_parameter(const std::string& n) const { return find_named(parameters, n); }
const Body* Model::find_body(const std::string& n) const { return find_named(bodies, n); }
const Ground* Model::find_ground(const std::string& n) const { return find_named(grounds, n); }

}  // namespace mbgen::ir
