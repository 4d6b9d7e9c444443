#include "emit/cse.hpp"

#include <algorithm>
#include <map>

#include "emit/infix_printer.hpp"

namespace mbgen::emit {
namespace {

using NodeCount = std::map<GiNaC::ex, int, GiNaC::ex_is_less>;

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

// Counts references from distinct parent occurrences in the DAG: a node's children are walked once only.
void count(const GiNaC::ex& e, NodeCount& uses, int weight) {
  auto [it, inserted] = uses.emplace(e, 0);
  it->second += weight;
  if (!inserted) return;
  int child_weight = product_power_uses(e);
  for (std::size_t i = 0; i < e.nops(); ++i) count(e.op(i), uses, i == 0 ? child_weight : 1);
}

struct Hoister {
  const NodeCount& uses;
  const std::string& prefix;
  std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less> replaced;  // hoisted node -> its symbol
  std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less> rewritten;  // memo: node -> node over temporaries
  std::map<GiNaC::ex, std::string, GiNaC::ex_is_less> texts;     // memo: node -> canonical infix text
  CseResult& result;

  GiNaC::ex rewrite(const GiNaC::ex& e) {
    if (is_leaf(e)) return e;
    if (auto it = replaced.find(e); it != replaced.end()) return it->second;
    GiNaC::ex body;
    if (auto it = rewritten.find(e); it != rewritten.end()) {
      body = it->second;
    } else {
      // Rebuild over rewritten children (evaluation cannot merge distinct temporaries).
      // Children are visited in the order of their text, not GiNaC's operand order (which follows the
      // addresses of type names and so changes from run to run): temporaries are numbered the same every run.
      GiNaC::exvector children(e.nops());
      bool changed = false;
      for (std::size_t i : canonical_order(e)) {
        children[i] = rewrite(e.op(i));
        changed = changed || !children[i].is_equal(e.op(i));
      }
      body = changed ? rebuild(e, children) : e;
      rewritten.emplace(e, body);
    }
    auto u = uses.find(e);
    if (u != uses.end() && u->second >= 2 && !is_trivial(e)) {
      GiNaC::symbol t(prefix + std::to_string(result.temporaries.size()));
      result.temporaries.emplace_back(t, body);
      replaced.emplace(e, t);
      return t;
    }
    return body;
  }

  std::vector<std::size_t> canonical_order(const GiNaC::ex& e) {
    std::vector<std::size_t> order(e.nops());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    if (!GiNaC::is_a<GiNaC::add>(e) && !GiNaC::is_a<GiNaC::mul>(e)) return order;
    std::vector<const std::string*> keys(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) keys[i] = &text_of(e.op(i));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return *keys[a] < *keys[b]; });
    return order;
  }

  const std::string& text_of(const GiNaC::ex& e) {
    auto it = texts.find(e);
    if (it == texts.end()) it = texts.emplace(e, infix_text(e)).first;
    return it->second;
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
  for (const auto& e : expressions) count(e, uses, 1);
  CseResult result;
  Hoister h{uses, prefix, {}, {}, {}, result};
  result.outputs.reserve(expressions.size());
  for (const auto& e : expressions) {
    // A whole output used twice is hoisted too; that is fine (it is then printed once).
    result.outputs.push_back(h.rewrite(e));
  }
  return result;
}

}  // namespace mbgen::emit
