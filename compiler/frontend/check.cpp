#include "frontend/check.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "frontend/diagnostics.hpp"
#include "ir/identifier.hpp"

namespace mbgen::frontend {

namespace {

class Checker {
 public:
  explicit Checker(ir::ModelIr& m) : m_(m) {}

  void run() {
    declare_all();
    check_parameters();
    for (ir::Body& b : m_.bodies) check_body(b);
    for (ir::Element& e : m_.elements) check_element(e);
    for (ir::Spin& s : m_.spins) check_spin(s);
    for (ir::Input& in : m_.inputs) {
      check_signal_frame(in.at, "input", in.name);
      check_direction(in.direction);
      if (in.gain) check_expr(*in.gain);
    }
    for (ir::Output& out : m_.outputs) {
      check_signal_frame(out.at, "output", out.name);
      check_direction(out.direction);
    }
    for (const ir::Filter& f : m_.filters) check_filter(f);
    check_connected();
  }

 private:
  [[noreturn]] void fail(ir::SourceLoc loc, const std::string& msg) const { throw ModelError(m_.file, loc, msg); }
  template <typename... Args>
  [[noreturn]] void fail(ir::SourceLoc loc, fmt::format_string<Args...> format, Args&&... args) const {
    throw ModelError(m_.file, loc, format, std::forward<Args>(args)...);
  }

  // Every name is declared once, whatever it names (docs/language.md): a parameter, a frame (ground or body), an
  // element and a signal (input or output) called alike would be confusing in messages, data and generated code.
  void declare(const std::string& what, const std::string& name, ir::SourceLoc loc) {
    const auto [it, fresh] = names_.emplace(name, Declared{what, loc});
    if (!fresh)
      fail(loc, "`{}` is already declared at line {}, column {} (as {}); each name is declared once", name,
           it->second.loc.line, it->second.loc.column, it->second.what);
  }

  void declare_all() {
    for (const ir::Parameter& p : m_.parameters) {
      if (ir::is_reserved_name(p.name)) fail(p.loc, "`{}` is reserved and cannot name a parameter", p.name);
      declare("a parameter", p.name, p.loc);
      params_.insert(p.name);
    }
    for (const ir::Ground& g : m_.grounds) declare("a ground", g.name, g.loc);
    for (const ir::Body& b : m_.bodies) declare("a body", b.name, b.loc);
    for (const ir::Element& e : m_.elements) declare("an element", e.name, e.loc);
    for (const ir::Input& in : m_.inputs) declare("an input", in.name, in.loc);
    for (const ir::Output& out : m_.outputs) declare("an output", out.name, out.loc);
    for (const ir::Filter& f : m_.filters) declare("a filter", f.name, f.loc);
  }

  void check_expr(const ir::Expr& e) const {
    if (e.kind == ir::Expr::Kind::Symbol) {
      if (e.text != "pi" && !params_.count(e.text)) {
        if (e.text == "inf") fail(e.loc, "`inf` is only allowed as a bound (`in [0, inf]`)");
        fail(e.loc, "unknown parameter `{}`: declare it with `param {} = VALUE`", e.text, e.text);
      }
      return;
    }
    for (const ir::Expr& a : e.args) check_expr(a);
  }

  void check_vec(const ir::Vec3& v) const {
    for (const ir::Expr& e : v) check_expr(e);
  }

  void check_parameters() {
    for (const ir::Parameter& p : m_.parameters) {
      check_expr(p.value);
      if (p.lower) check_expr(*p.lower);
      if (p.upper) check_expr(*p.upper);
    }
    // Cycles among derived parameters, and how deeply each nests with the parameters it uses written out (the
    // symbolic stage substitutes them): depth-first, memoized, and the recursion itself bounded by that depth.
    for (const ir::Parameter& p : m_.parameters) expanded_depth(p, 0);
  }

  // Depth of `p`'s value with the derived parameters it uses written out (each substitution adds a level).
  // `above`: levels above it in the expansion being computed; past the limit the top parameter is too deep.
  int expanded_depth(const ir::Parameter& p, int above) {
    if (const auto done = depth_.find(p.name); done != depth_.end()) return done->second;
    if (std::find(expanding_.begin(), expanding_.end(), &p) != expanding_.end())
      fail(p.loc, "parameter `{}` is defined in terms of itself", p.name);
    expanding_.push_back(&p);
    const int depth = value_depth(p.value, above);
    expanding_.pop_back();
    if (depth > ir::kMaxExpressionDepth) fail(p.loc, too_deep(p));
    depth_[p.name] = depth;
    return depth;
  }

  int value_depth(const ir::Expr& e, int above) {
    if (above >= ir::kMaxExpressionDepth) fail(expanding_.front()->loc, too_deep(*expanding_.front()));
    if (e.kind == ir::Expr::Kind::Symbol) {
      const ir::Parameter* q = m_.find_parameter(e.text);
      return q && q->derived ? 1 + expanded_depth(*q, above + 1) : 1;
    }
    int deepest = 0;
    for (const ir::Expr& a : e.args) deepest = std::max(deepest, value_depth(a, above + 1));
    return deepest + 1;
  }

  std::string too_deep(const ir::Parameter& p) const {
    return fmt::format("parameter `{}` nests too deeply: with the derived parameters it uses written out, its value "
                       "has more than {} levels of operators and parameters",
                       p.name, ir::kMaxExpressionDepth);
  }

  void check_body(ir::Body& b) {
    check_expr(b.mass);
    for (const auto& j : b.inertia)
      if (j) check_expr(*j);
    check_vec(b.position);
    if (b.dofs.empty()) fail(b.loc, "body `{}` has no coordinates: give it a `dof` line (x y z rx ry rz)", b.name);
  }

  // Resolves the frame and fills an implicit point.
  void resolve(ir::Attachment& a) const {
    if (const ir::Body* b = m_.find_body(a.frame)) {
      if (!a.has_point) a.point = b->position;
    } else if (!m_.is_ground(a.frame)) {
      fail(a.loc, "unknown frame `{}`: expected the name of a body or a ground", a.frame);
    }
    check_vec(a.point);
  }

  void check_direction(const ir::Direction& d) const {
    check_vec(d.vector);
    bool all_zero = true;
    for (const ir::Expr& e : d.vector) all_zero = all_zero && e.is_number() && ir::is_zero_literal(e.text);
    if (all_zero) fail(d.loc, "a direction must not be the zero vector");
  }

  void check_element(ir::Element& e) {
    resolve(e.a);
    resolve(e.b);
    if (e.a.frame == e.b.frame) fail(e.b.loc, "element `{}` joins `{}` to itself", e.name, e.a.frame);
    if (m_.is_ground(e.a.frame) && m_.is_ground(e.b.frame))
      fail(e.b.loc, "element `{}` joins two grounds: it would do nothing", e.name);
    if (e.kind != ir::ElementKind::Spring3) check_direction(e.direction);
    for (const ir::Expr& k : e.stiffness) check_expr(k);
    for (const ir::Expr& c : e.damping) check_expr(c);
  }

  void check_spin(ir::Spin& s) {
    if (!m_.find_body(s.body)) fail(s.loc, "unknown body `{}`: only a body can spin", s.body);
    check_expr(s.speed);
    if (!spinning_.insert(s.body).second) fail(s.loc, "body `{}` is given a spin twice", s.body);
  }

  void check_signal_frame(ir::Attachment& a, const std::string& what, const std::string& name) {
    if (m_.is_ground(a.frame))
      fail(a.loc, "{} `{}` is on ground `{}`, which does not move: put it on a body", what, name, a.frame);
    resolve(a);
  }

  void check_filter(const ir::Filter& f) const {
    const bool is_output = std::any_of(m_.outputs.begin(), m_.outputs.end(),
                                       [&](const ir::Output& o) { return o.name == f.output; });
    if (!is_output) fail(f.loc, "filter `{}` is on `{}`, which is not an output", f.name, f.output);
    for (const std::optional<ir::Expr>* e : {&f.cutoff, &f.damping, &f.time, &f.factor})
      if (*e) check_expr(**e);
  }

  // Every body must be held by some element; otherwise it floats free or is forgotten.
  void check_connected() const {
    std::set<std::string> connected;
    for (const ir::Element& e : m_.elements) {
      connected.insert(e.a.frame);
      connected.insert(e.b.frame);
    }
    for (const ir::Body& b : m_.bodies)
      if (!connected.count(b.name))
        fail(b.loc, "body `{}` is not connected: no spring, spring3 or torsion element attaches to it", b.name);
  }

  struct Declared {
    std::string what;
    ir::SourceLoc loc;
  };
  ir::ModelIr& m_;
  std::map<std::string, Declared> names_;
  std::set<std::string> params_;
  std::map<std::string, int> depth_;                // expanded depth of each parameter visited
  std::vector<const ir::Parameter*> expanding_;   // the chain being expanded (cycle check)
  std::set<std::string> spinning_;
};

}  // namespace

void check_model(ir::ModelIr& model) { Checker(model).run(); }

}  // namespace mbgen::frontend
