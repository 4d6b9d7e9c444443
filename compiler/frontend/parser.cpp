#include "frontend/parser.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "frontend/check.hpp"
#include "frontend/diagnostics.hpp"
#include "frontend/lexer.hpp"
#include "ir/identifier.hpp"

namespace mbgen::frontend {

namespace {

using ir::Expr;
using ir::SourceLoc;

class Parser {
 public:
  Parser(std::vector<Token> tokens, std::string file) : tokens_(std::move(tokens)), file_(std::move(file)) {}

  ir::ModelIr run() {
    model_.file = file_;
    skip_newlines();
    while (peek().kind != TokenKind::End) {
      statement();
      skip_newlines();
    }
    return std::move(model_);
  }

 private:
  // ---- token helpers -------------------------------------------------------------------------------
  const Token& peek() const { return tokens_[i_]; }
  const Token& next() { return tokens_[i_ < tokens_.size() - 1 ? i_++ : i_]; }
  bool at_punct(const char* p) const { return peek().kind == TokenKind::Punct && peek().text == p; }
  bool at_word(const char* w) const { return peek().kind == TokenKind::Name && peek().text == w; }

  [[noreturn]] void fail(const Token& t, const std::string& expected) const {
    throw ModelError(file_, t.loc, "expected " + expected + ", found " + describe(t));
  }
  [[noreturn]] void fail_at(SourceLoc loc, const std::string& message) const { throw ModelError(file_, loc, message); }

  void expect_punct(const char* p) {
    if (!at_punct(p)) fail(peek(), std::string("`") + p + "`");
    next();
  }
  void expect_word(const char* w) {
    if (!at_word(w)) fail(peek(), std::string("`") + w + "`");
    next();
  }
  Token expect_name(const std::string& what) {
    if (peek().kind != TokenKind::Name) fail(peek(), what);
    return next();
  }
  void skip_newlines() {
    while (peek().kind == TokenKind::Newline || at_punct(";")) next();
  }
  // A statement ends at a newline, `;`, the end of the file, or (inside a block) before `}`.
  void end_statement() {
    if (peek().kind == TokenKind::Newline || at_punct(";")) {
      next();
      return;
    }
    if (peek().kind == TokenKind::End || at_punct("}")) return;
    fail(peek(), "end of statement (a new line or `;`)");
  }

  // ---- statements ----------------------------------------------------------------------------------
  void statement() {
    const Token& t = peek();
    if (t.kind != TokenKind::Name)
      fail(t, "a statement (model, param, ground, body, spring, spring3, torsion, spin, input, output, filter)");
    const std::string kw = t.text;
    if (kw == "model") return model_statement();
    if (kw == "param") return param_statement();
    if (kw == "ground") return ground_statement();
    if (kw == "body") return body_statement();
    if (kw == "spring") return element_statement(ir::ElementKind::Spring);
    if (kw == "spring3") return element_statement(ir::ElementKind::Spring3);
    if (kw == "torsion") return element_statement(ir::ElementKind::Torsion);
    if (kw == "spin") return spin_statement();
    if (kw == "input") return input_statement();
    if (kw == "output") return output_statement();
    if (kw == "filter") return filter_statement();
    fail(t, "a statement (model, param, ground, body, spring, spring3, torsion, spin, input, output, filter)");
  }

  void model_statement() {
    const Token kw = next();
    if (!model_.name.empty()) fail_at(kw.loc, "a second `model` statement: the model is already named `" + model_.name + "`");
    const Token name = expect_name("the model's name");
    model_.name = name.text;
    model_.name_loc = name.loc;
    end_statement();
  }

  void param_statement() {
    next();
    ir::Parameter p;
    const Token name = expect_name("a parameter name");
    p.name = name.text;
    p.loc = name.loc;
    expect_punct("=");
    p.value = expr();
    p.derived = !ir::symbols_of(p.value).empty();
    if (peek().kind == TokenKind::String) p.unit = next().text;
    bool role_given = false;
    if (at_word("known") || at_word("estimate") || at_word("fixed")) {
      const Token r = next();
      p.role = r.text == "known" ? ir::Role::Known : r.text == "estimate" ? ir::Role::Estimate : ir::Role::Fixed;
      role_given = true;
      if (p.derived && p.role == ir::Role::Estimate)
        fail_at(r.loc, "parameter `" + p.name + "` is derived (an expression of other parameters) and cannot be `estimate`; estimate the parameters it is built from");
    }
    if (at_word("in")) {
      next();
      expect_punct("[");
      p.lower = bound();
      expect_punct(",");
      p.upper = bound();
      expect_punct("]");
    }
    if (peek().kind == TokenKind::String && !role_given)
      fail(peek(), "a role (known, estimate, fixed) or bounds (`in [LOWER, UPPER]`): the unit comes right after the value");
    if (peek().kind != TokenKind::Newline && !at_punct(";") && peek().kind != TokenKind::End)
      fail(peek(), "a unit string, a role (known, estimate, fixed), bounds `in [LOWER, UPPER]` or the end of the statement");
    end_statement();
    model_.parameters.push_back(std::move(p));
  }

  // A bound: an expression, or `inf` / `-inf` for an open end.
  std::optional<Expr> bound() {
    if (at_word("inf")) {
      next();
      return std::nullopt;
    }
    if (at_punct("-") && tokens_[i_ + 1].kind == TokenKind::Name && tokens_[i_ + 1].text == "inf") {
      next();
      next();
      return std::nullopt;
    }
    return expr();
  }

  void ground_statement() {
    next();
    const Token name = expect_name("a ground name");
    model_.grounds.push_back({name.text, name.loc});
    end_statement();
  }

  void open_block() {
    expect_punct("{");
    skip_newlines();
  }

  // Runs `item` for each statement of a { } block.
  template <typename F>
  void block(F item) {
    open_block();
    while (!at_punct("}")) {
      if (peek().kind == TokenKind::End) fail(peek(), "`}` to close the block");
      item();
      skip_newlines();
    }
    next();
    end_statement();
  }

  void body_statement() {
    next();
    ir::Body b;
    const Token name = expect_name("a body name");
    b.name = name.text;
    b.loc = name.loc;
    b.position = zero_vec(name.loc);
    bool has_mass = false, has_inertia = false, has_at = false, has_dof = false;
    auto once = [&](bool& seen, const Token& t) {
      if (seen) fail_at(t.loc, "`" + t.text + "` given twice in body `" + b.name + "`");
      seen = true;
    };
    block([&] {
      const Token t = expect_name("a body item (mass, inertia, at, dof)");
      if (t.text == "mass") {
        once(has_mass, t);
        b.mass = expr();
      } else if (t.text == "inertia") {
        once(has_inertia, t);
        std::vector<Expr> v = expr_list();
        if (v.size() != 3 && v.size() != 6)
          fail_at(t.loc, "`inertia` takes 3 values (XX, YY, ZZ) or 6 (XX, YY, ZZ, XY, XZ, YZ), found " + std::to_string(v.size()));
        for (std::size_t k = 0; k < v.size(); ++k) b.inertia[k] = std::move(v[k]);
      } else if (t.text == "at") {
        once(has_at, t);
        b.position = vec3();
      } else if (t.text == "dof") {
        once(has_dof, t);
        dofs(b);
      } else {
        fail(t, "a body item (mass, inertia, at, dof)");
      }
      end_statement();
    });
    if (!has_mass) fail_at(b.loc, "body `" + b.name + "` has no `mass`");
    model_.bodies.push_back(std::move(b));
  }

  void dofs(ir::Body& b) {
    static const char* names[] = {"x", "y", "z", "rx", "ry", "rz"};
    do {
      if (at_punct(",")) next();
      const Token t = expect_name("a coordinate (x, y, z, rx, ry, rz)");
      int k = 0;
      while (k < 6 && t.text != names[k]) ++k;
      if (k == 6) fail(t, "a coordinate (x, y, z, rx, ry, rz)");
      const ir::Dof d = static_cast<ir::Dof>(k);
      for (ir::Dof seen : b.dofs)
        if (seen == d) fail_at(t.loc, "coordinate `" + t.text + "` given twice for body `" + b.name + "`");
      b.dofs.push_back(d);
    } while (peek().kind == TokenKind::Name || at_punct(","));
  }

  void element_statement(ir::ElementKind kind) {
    const Token kw = next();
    ir::Element e;
    e.kind = kind;
    const Token name = expect_name("an element name");
    e.name = name.text;
    e.loc = name.loc;
    bool has_from = false, has_to = false, has_dir = false, has_k = false, has_c = false;
    const std::size_t count = kind == ir::ElementKind::Spring3 ? 3 : 1;
    const char* dir_word = kind == ir::ElementKind::Torsion ? "about" : "along";
    const std::string items = kind == ir::ElementKind::Spring3 ? "from, to, stiffness, damping"
                                                                 : std::string("from, to, ") + dir_word + ", stiffness, damping";
    auto once = [&](bool& seen, const Token& t) {
      if (seen) fail_at(t.loc, "`" + t.text + "` given twice in " + kw.text + " `" + e.name + "`");
      seen = true;
    };
    auto values = [&](const Token& t) {
      std::vector<Expr> v = expr_list();
      if (v.size() != count)
        fail_at(t.loc, "a " + kw.text + " takes " + std::to_string(count) + (count == 1 ? " value" : " values (x, y, z)") +
                           " for `" + t.text + "`, found " + std::to_string(v.size()));
      return v;
    };
    block([&] {
      const Token t = expect_name("an element item (" + items + ")");
      if (t.text == "from") {
        once(has_from, t);
        e.a = attachment(kind != ir::ElementKind::Torsion);
      } else if (t.text == "to") {
        once(has_to, t);
        e.b = attachment(kind != ir::ElementKind::Torsion);
      } else if (kind != ir::ElementKind::Spring3 && t.text == dir_word) {
        once(has_dir, t);
        e.direction = direction();
      } else if (t.text == "stiffness") {
        once(has_k, t);
        e.stiffness = values(t);
      } else if (t.text == "damping") {
        once(has_c, t);
        e.damping = values(t);
      } else {
        fail(t, "an element item (" + items + ")");
      }
      end_statement();
    });
    if (!has_from) fail_at(e.loc, kw.text + " `" + e.name + "` has no `from`");
    if (!has_to) fail_at(e.loc, kw.text + " `" + e.name + "` has no `to`");
    if (kind != ir::ElementKind::Spring3 && !has_dir)
      fail_at(e.loc, kw.text + " `" + e.name + "` has no `" + dir_word + "` direction");
    if (!has_k) fail_at(e.loc, kw.text + " `" + e.name + "` has no `stiffness`");
    model_.elements.push_back(std::move(e));
  }

  void spin_statement() {
    next();
    ir::Spin s;
    const Token body = expect_name("the name of the spinning body");
    s.body = body.text;
    s.loc = body.loc;
    expect_word("about");
    const Token axis = expect_name("a spin axis (x, y or z)");
    if (axis.text != "x" && axis.text != "y" && axis.text != "z") fail(axis, "a spin axis (x, y or z)");
    s.axis = axis.text;
    expect_word("speed");
    s.speed = expr();
    end_statement();
    model_.spins.push_back(std::move(s));
  }

  void input_statement() {
    next();
    ir::Input in;
    const Token name = expect_name("an input name");
    in.name = name.text;
    in.loc = name.loc;
    const Token kind = expect_name("`force` or `moment`");
    if (kind.text == "force") in.kind = ir::InputKind::Force;
    else if (kind.text == "moment") in.kind = ir::InputKind::Moment;
    else fail(kind, "`force` or `moment`");
    expect_word("on");
    in.at = attachment(in.kind == ir::InputKind::Force);
    expect_word("along");
    in.direction = direction();
    if (at_word("gain")) {
      next();
      const SourceLoc gain_loc = peek().loc;
      in.gain = expr();
      if (is_zero_constant(*in.gain))
        fail_at(gain_loc, "input `" + in.name + "`: its gain is 0: its record would read no force (a gain is what the "
                          "record reads per unit of the applied force, e.g. 0.98, or -1 for a reversed sign)");
    }
    end_statement();
    model_.inputs.push_back(std::move(in));
  }

  void output_statement() {
    next();
    ir::Output out;
    const Token name = expect_name("an output name");
    out.name = name.text;
    out.loc = name.loc;
    const Token kind = expect_name("`displacement`, `velocity` or `acceleration`");
    if (kind.text == "displacement") out.kind = ir::OutputKind::Displacement;
    else if (kind.text == "velocity") out.kind = ir::OutputKind::Velocity;
    else if (kind.text == "acceleration") out.kind = ir::OutputKind::Acceleration;
    else fail(kind, "`displacement`, `velocity` or `acceleration`");
    expect_word("of");
    out.at = attachment(true);
    expect_word("along");
    out.direction = direction();
    end_statement();
    model_.outputs.push_back(std::move(out));
  }

  // filter NAME on OUTPUT lowpass2|highpass1|highpass2|delay|gain ITEM...   (docs/language.md, "Filters")
  void filter_statement() {
    next();
    ir::Filter f;
    const Token name = expect_name("a filter name");
    f.name = name.text;
    f.loc = name.loc;
    expect_word("on");
    f.output = expect_name("the name of the output it filters").text;
    const char* kinds = "a filter kind (lowpass2, highpass1, highpass2, delay, gain)";
    const Token kind = expect_name(kinds);
    if (kind.text == "lowpass2") f.kind = ir::FilterKind::Lowpass2;
    else if (kind.text == "highpass1") f.kind = ir::FilterKind::Highpass1;
    else if (kind.text == "highpass2") f.kind = ir::FilterKind::Highpass2;
    else if (kind.text == "delay") f.kind = ir::FilterKind::Delay;
    else if (kind.text == "gain") f.kind = ir::FilterKind::Gain;
    else fail(kind, kinds);
    const bool delay = f.kind == ir::FilterKind::Delay;
    const bool gain = f.kind == ir::FilterKind::Gain;
    const bool second_order = f.kind == ir::FilterKind::Lowpass2 || f.kind == ir::FilterKind::Highpass2;
    const std::string items = delay          ? "`time` or `sections`"
                              : gain         ? "`factor`"
                              : second_order ? "`cutoff` or `damping`"
                                             : "`cutoff`";
    bool has_sections = false;
    while (peek().kind == TokenKind::Name) {
      const Token item = next();
      const auto once = [&](bool seen) {
        if (seen) fail_at(item.loc, "`" + item.text + "` given twice in filter `" + f.name + "`");
      };
      if (gain && item.text == "factor") {
        once(f.factor.has_value());
        f.factor = expr();
      } else if (!delay && !gain && item.text == "cutoff") {
        once(f.cutoff.has_value());
        f.cutoff = expr();
      } else if (second_order && item.text == "damping") {
        once(f.damping.has_value());
        f.damping = expr();
      } else if (delay && item.text == "time") {
        once(f.time.has_value());
        f.time = expr();
      } else if (delay && item.text == "sections") {
        once(has_sections);
        has_sections = true;
        const Token n = next();
        if (n.kind != TokenKind::Number || n.text.find_first_not_of("0123456789") != std::string::npos ||
            n.text.size() > 2 || std::stoi(n.text) < 1 || std::stoi(n.text) > 16)
          fail(n, "a whole number of sections from 1 to 16");
        f.sections = std::stoi(n.text);
      } else {
        fail(item, std::string(ir::to_string(f.kind)) + " filter item (" + items + ")");
      }
    }
    const auto require = [&](const std::optional<Expr>& e, const char* word) {
      if (!e) fail_at(f.loc, std::string(ir::to_string(f.kind)) + " filter `" + f.name + "` has no `" + word + "`");
    };
    if (delay) {
      require(f.time, "time");
    } else if (gain) {
      require(f.factor, "factor");
    } else {
      require(f.cutoff, "cutoff");
      if (second_order) require(f.damping, "damping");
    }
    end_statement();
    model_.filters.push_back(std::move(f));
  }

  // ---- pieces --------------------------------------------------------------------------------------
  ir::Attachment attachment(bool point_allowed) {
    ir::Attachment a;
    const Token frame = expect_name("a body or ground name");
    a.frame = frame.text;
    a.loc = frame.loc;
    a.point = zero_vec(frame.loc);
    if (at_word("at")) {
      if (!point_allowed) fail_at(peek().loc, "a point (`at`) has no meaning here: rotations do not depend on the point");
      next();
      a.point = vec3();
      a.has_point = true;
    }
    return a;
  }

  ir::Direction direction() {
    ir::Direction d;
    d.loc = peek().loc;
    if (at_punct("(")) {
      d.vector = vec3();
      return d;
    }
    const Token axis = expect_name("a direction: x, y, z or a vector (A, B, C)");
    if (axis.text != "x" && axis.text != "y" && axis.text != "z") fail(axis, "a direction: x, y, z or a vector (A, B, C)");
    d.axis = axis.text;
    for (int k = 0; k < 3; ++k) d.vector[k] = Expr::number(std::string(1, "xyz"[k]) == axis.text ? "1" : "0", axis.loc);
    return d;
  }

  // Zero whatever the parameters' values: a zero literal, its negation, a product with a zero factor, a zero over
  // anything. (A gain that is zero only at some parameter values is caught by the symbolic stage.)
  static bool is_zero_constant(const Expr& e) {
    switch (e.kind) {
      case Expr::Kind::Number: return ir::is_zero_literal(e.text);
      case Expr::Kind::Neg: return is_zero_constant(e.args[0]);
      case Expr::Kind::Div: return is_zero_constant(e.args[0]);
      case Expr::Kind::Mul: return std::any_of(e.args.begin(), e.args.end(), is_zero_constant);
      default: return false;
    }
  }

  static ir::Vec3 zero_vec(SourceLoc loc) { return {Expr::number("0", loc), Expr::number("0", loc), Expr::number("0", loc)}; }

  ir::Vec3 vec3() {
    expect_punct("(");
    Expr x = expr();
    expect_punct(",");
    Expr y = expr();
    expect_punct(",");
    Expr z = expr();
    expect_punct(")");
    return {std::move(x), std::move(y), std::move(z)};
  }

  std::vector<Expr> expr_list() {
    std::vector<Expr> v{expr()};
    while (at_punct(",")) {
      next();
      v.push_back(expr());
    }
    return v;
  }

  // ---- expressions ---------------------------------------------------------------------------------
  // Each level returns its expression with the expression's depth (a leaf is 1). Sums and products are n-ary
  // nodes (`a - b` is a term Neg(b) of a sum), so a long sum or product is flat; nesting (parentheses, unary
  // minus, powers, calls, divisions) is limited to ir::kMaxExpressionDepth, which keeps every recursive pass
  // over an expression (here, the checks, GiNaC) far from the end of the stack.
  struct Parsed {
    Expr e;
    int depth = 1;
  };

  Parsed limited(Parsed p, SourceLoc loc) const {
    if (p.depth > ir::kMaxExpressionDepth) fail_at(loc, too_deep());
    return p;
  }
  static std::string too_deep() {
    return "expression nested too deeply: at most " + std::to_string(ir::kMaxExpressionDepth) +
           " levels of parentheses, operators and function calls";
  }

  Expr expr() { return sum().e; }

  Parsed sum() {
    Parsed first = product();
    if (!at_punct("+") && !at_punct("-")) return first;
    const SourceLoc loc = peek().loc;
    Expr node = Expr::sum({}, loc);
    int depth = first.depth;
    node.args.push_back(std::move(first.e));
    while (at_punct("+") || at_punct("-")) {
      const Token op = next();
      Parsed term = product();
      if (op.text == "-") {
        term.e = Expr::negate(std::move(term.e), op.loc);
        ++term.depth;
      }
      depth = std::max(depth, term.depth);
      node.args.push_back(std::move(term.e));
    }
    return limited({std::move(node), depth + 1}, loc);
  }

  // Runs of `*` make one product; a `/` divides everything to its left: a*b/c*d is ((a*b)/c)*d.
  Parsed product() {
    Parsed left = unary();
    std::vector<Parsed> factors;  // multiplied onto `left`
    SourceLoc times_loc;
    auto close_product = [&] {
      if (factors.empty()) return;
      Expr node = Expr::product({}, times_loc);
      int depth = left.depth;
      node.args.push_back(std::move(left.e));
      for (Parsed& f : factors) {
        depth = std::max(depth, f.depth);
        node.args.push_back(std::move(f.e));
      }
      factors.clear();
      left = limited({std::move(node), depth + 1}, times_loc);
    };
    while (at_punct("*") || at_punct("/")) {
      const Token op = next();
      Parsed right = unary();
      if (op.text == "*") {
        if (factors.empty()) times_loc = op.loc;
        factors.push_back(std::move(right));
        continue;
      }
      close_product();
      const int depth = std::max(left.depth, right.depth) + 1;
      left = limited({Expr::binary(Expr::Kind::Div, std::move(left.e), std::move(right.e), op.loc), depth}, op.loc);
    }
    close_product();
    return left;
  }

  // Every recursion of the expression grammar passes here, so the nesting count bounds the parser's own stack.
  Parsed unary() {
    if (++nesting_ > ir::kMaxExpressionDepth) fail_at(peek().loc, too_deep());
    Parsed out;
    if (at_punct("-")) {
      const Token op = next();
      Parsed operand = unary();
      out = limited({Expr::negate(std::move(operand.e), op.loc), operand.depth + 1}, op.loc);
    } else {
      out = power();
    }
    --nesting_;
    return out;
  }

  Parsed power() {
    Parsed base = primary();
    if (at_punct("^")) {
      const Token op = next();
      Parsed exponent = unary();
      const int depth = std::max(base.depth, exponent.depth) + 1;
      return limited({Expr::binary(Expr::Kind::Pow, std::move(base.e), std::move(exponent.e), op.loc), depth}, op.loc);
    }
    return base;
  }

  Parsed primary() {
    const Token& t = peek();
    if (t.kind == TokenKind::Number) {
      next();
      return {Expr::number(t.text, t.loc), 1};
    }
    if (t.kind == TokenKind::Name) {
      const Token name = next();
      if (!at_punct("(")) return {Expr::symbol(name.text, name.loc), 1};
      if (name.text != "sqrt" && name.text != "sin" && name.text != "cos")
        fail_at(name.loc, "unknown function `" + name.text + "`: the functions are sqrt, sin and cos");
      next();
      Parsed arg = sum();
      if (at_punct(",")) {
        std::size_t count = 1;
        while (at_punct(",")) {
          next();
          sum();
          ++count;
        }
        fail_at(name.loc, "`" + name.text + "` takes one argument, found " + std::to_string(count));
      }
      expect_punct(")");
      std::vector<Expr> args;
      args.push_back(std::move(arg.e));
      return limited({Expr::call(name.text, std::move(args), name.loc), arg.depth + 1}, name.loc);
    }
    if (at_punct("(")) {
      next();
      Parsed inner = sum();
      expect_punct(")");
      return inner;
    }
    fail(t, "an expression (a number, a parameter name or `(`)");
  }

  std::vector<Token> tokens_;
  std::string file_;
  std::size_t i_ = 0;
  int nesting_ = 0;  // recursion depth of unary()
  ir::ModelIr model_;
};

// The model's name defaults to the file's stem, made a valid identifier (it names a C++ namespace).
std::string stem_of(const std::string& path) {
  std::string base = path.substr(path.find_last_of('/') + 1);
  const std::size_t dot = base.find_last_of('.');
  if (dot != std::string::npos && dot != 0) base = base.substr(0, dot);
  return ir::to_identifier(base);
}

}  // namespace

ir::ModelIr parse_string(const std::string& text, const std::string& file_name) {
  ir::ModelIr model = Parser(tokenize(text, file_name), file_name).run();
  if (model.name.empty()) model.name = file_name == "-" || file_name.empty() ? "model" : stem_of(file_name);
  check_model(model);
  return model;
}

namespace {

// The whole of `in`, refused beyond kMaxModelBytes: `inspect /dev/zero` (or a stray multi-gigabyte file) read until
// the memory ran out.
std::string read_bounded(std::istream& in, const std::string& path) {
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxModelBytes)
      throw ModelError(path, {}, "the model file is larger than {} MiB (docs/limits.md)", kMaxModelBytes >> 20);
  }
  if (in.bad()) throw ModelError(path, {}, "cannot read the model file");
  return text;
}

}  // namespace

std::string read_model_text(const std::string& path) {
  if (path == "-") return read_bounded(std::cin, path);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw ModelError(path, {}, "is a directory, not a model file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(path, {}, "cannot open the model file");
  return read_bounded(in, path);
}

ir::ModelIr parse_file(const std::string& path) { return parse_string(read_model_text(path), path); }

}  // namespace mbgen::frontend
