#include "passes/cse.hpp"

#include <map>
#include <numeric>

#include "passes/sign_free_key.hpp"

namespace mbgen::passes {
namespace {

using NodeCount = std::map<std::string, int>;

bool is_leaf(const GiNaC::ex& e) {
  return GiNaC::is_a<GiNaC::symbol>(e) || GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::constant>(e);
}

// Nodes not worth a temporary: leaves and a number times a leaf (e.g. -k12, 2*m1).
bool is_trivial(const GiNaC::ex& e) {
  if (is_leaf(e)) return true;
  if (GiNaC::is_a<GiNaC::mul>(e) && e.nops() == 2) {
    return (GiNaC::is_a<GiNaC::numeric>(e.op(0)) && is_leaf(e.op(1))) ||
           (GiNaC::is_a<GiNaC::numeric>(e.op(1)) && is_leaf(e.op(0)));
  }
  return false;
}

// A small positive integer power the printer writes as a product (x*x*x): its base counts once per factor.
int product_power_uses(const GiNaC::ex& e) {
  if (!GiNaC::is_a<GiNaC::power>(e)) return 1;
  const GiNaC::ex& n = e.op(1);
  if (!n.info(GiNaC::info_flags::integer)) return 1;
  int k = GiNaC::ex_to<GiNaC::numeric>(n).to_int();
  if (k < 0) k = -k;
  return (k >= 2 && k <= 4) ? k : 1;
}

// Counts references from distinct parent occurrences in the DAG: a node's children are walked once only. Nodes
// are counted by their sign-free key, so that e and -e are one node: GiNaC writes a subexpression with one sign
// in one place and the other elsewhere, and which sign where changes from run to run (see sign_free_key.hpp).
void count(const GiNaC::ex& node, NodeCount& uses, SignFreeKeys& keys, int weight) {
  const GiNaC::ex e = strip_unit_factor(node).first;
  auto [it, inserted] = uses.emplace(keys.key(e), 0);
  it->second += weight;
  if (!inserted) return;
  int child_weight = product_power_uses(e);
  for (std::size_t i = 0; i < e.nops(); ++i) count(e.op(i), uses, keys, i == 0 ? child_weight : 1);
}

struct Hoister {
  const NodeCount& uses;
  SignFreeKeys& keys;
  const std::string& prefix;
  // Hoisted nodes by key -> (temporary, s): the node n with that key is sign(n)*s*temporary.
  std::map<std::string, std::pair<GiNaC::symbol, int>> replaced;
  std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less> rewritten;  // memo: node -> node over temporaries
  CseResult& result;

  GiNaC::ex rewrite(const GiNaC::ex& node) {
    const auto [e, unit] = strip_unit_factor(node);
    if (unit != 1) return -rewrite(e);
    if (is_leaf(e)) return e;
    const std::string& key = keys.key(e);
    if (auto it = replaced.find(key); it != replaced.end()) return keys.sign(e) * it->second.second * it->second.first;
    GiNaC::ex body;
    if (auto it = rewritten.find(e); it != rewritten.end()) {
      body = it->second;
    } else {
      // Rebuild over rewritten children (evaluation cannot merge distinct temporaries).
      // Children are visited in the order of their keys, not GiNaC's operand order (which follows hash values and
      // so changes from run to run): temporaries are numbered the same every run.
      GiNaC::exvector children(e.nops());
      bool changed = false;
      std::vector<std::size_t> order(e.nops());
      std::iota(order.begin(), order.end(), std::size_t{0});
      if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) order = keys.operand_order(e);
      for (std::size_t i : order) {
        children[i] = rewrite(e.op(i));
        changed = changed || !children[i].is_equal(e.op(i));
      }
      body = changed ? rebuild(e, children) : e;
      rewritten.emplace(e, body);
    }
    auto u = uses.find(key);
    if (u != uses.end() && u->second >= 2 && !is_trivial(e)) {
      // The temporary holds the body's magnitude, the same expression in every run; e is ±that.
      GiNaC::symbol t(prefix + std::to_string(result.temporaries.size()));
      const int body_sign = keys.sign(body);
      result.temporaries.emplace_back(t, body_sign * body);
      replaced.emplace(key, std::make_pair(t, keys.sign(e) * body_sign));
      return body_sign * t;
    }
    return body;
  }

  static GiNaC::ex rebuild(const GiNaC::ex& e, const GiNaC::exvector& c) {
    if (GiNaC::is_a<GiNaC::add>(e)) {
      GiNaC::ex s = 0;
      for (const auto& x : c) s += x;
      return s;
    }
    if (GiNaC::is_a<GiNaC::mul>(e)) {
      GiNaC::ex p = 1;
      for (const auto& x : c) p *= x;
      return p;
    }
    if (GiNaC::is_a<GiNaC::power>(e)) return GiNaC::pow(c[0], c[1]);
    // Functions and anything else: substitute operands in place.
    GiNaC::ex r = e;
    for (std::size_t i = 0; i < c.size(); ++i) r.let_op(i) = c[i];
    return r;
  }
};

}  // namespace

CseResult eliminate_common_subexpressions(const std::vector<GiNaC::ex>& expressions, const std::string& prefix) {
  NodeCount uses;
  SignFreeKeys keys;
  for (const auto& e : expressions) count(e, uses, keys, 1);
  CseResult result;
  Hoister h{uses, keys, prefix, {}, {}, result};
  result.outputs.reserve(expressions.size());
  for (const auto& e : expressions) {
    // A whole output used twice is hoisted too; that is fine (it is then printed once).
    result.outputs.push_back(h.rewrite(e));
  }
  return result;
}

}  // namespace mbgen::passes
