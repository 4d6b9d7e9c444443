#include "elimination/elimination.hpp"

#include <algorithm>
#include <optional>
#include <tuple>

namespace mbgen::elimination {

namespace {

struct State {
  std::vector<GiNaC::ex> equations;  // polynomial, expanded; zero once used or dropped
  std::vector<bool> open;            // still to be solved or checked
  std::vector<GiNaC::ex> values;     // per unknown: its solution in the unknowns not yet solved (or the symbol)
  std::vector<bool> solved;
  EliminationBranch branch;
};

bool has_unknown(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& unknowns, const std::vector<bool>& solved) {
  for (std::size_t u = 0; u < unknowns.size(); ++u)
    if (!solved[u] && e.has(unknowns[u])) return true;
  return false;
}

// numer(normal(e)), expanded, without monomial factors of the unknowns.
GiNaC::ex tidy(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& unknowns) {
  GiNaC::ex p = GiNaC::expand(GiNaC::normal(e).numer());
  if (p.is_zero()) return p;
  for (const GiNaC::symbol& x : unknowns) {
    const int low = p.ldegree(x);
    if (low > 0) p = GiNaC::expand(p * GiNaC::pow(x, -low));
  }
  return p;
}

std::size_t terms(const GiNaC::ex& e) { return GiNaC::is_a<GiNaC::add>(e) ? e.nops() : 1; }

// Substitutes x = value everywhere.
void substitute(State& st, const std::vector<GiNaC::symbol>& unknowns, std::size_t x, const GiNaC::ex& value) {
  st.values[x] = value;
  st.solved[x] = true;
  for (std::size_t u = 0; u < unknowns.size(); ++u)
    if (u != x) st.values[u] = GiNaC::normal(st.values[u].subs(unknowns[x] == value));
  for (std::size_t i = 0; i < st.equations.size(); ++i)
    if (st.open[i]) st.equations[i] = tidy(st.equations[i].subs(unknowns[x] == value), unknowns);
}

// Runs elimination on one state to its end; appends finished branches to `out`, pushes splits to `stack`.
std::string run(State st, const std::vector<GiNaC::symbol>& unknowns, bool square, const EliminationLimits& limits,
                std::vector<State>& stack, std::vector<EliminationBranch>& out) {
  const std::size_t n = unknowns.size();
  for (;;) {
    // Judge the open equations.
    for (std::size_t i = 0; i < st.equations.size(); ++i) {
      if (!st.open[i]) continue;
      const GiNaC::ex& e = st.equations[i];
      if (terms(e) > limits.max_terms)
        return "an equation grew beyond " + std::to_string(limits.max_terms) + " terms";
      if (has_unknown(e, unknowns, st.solved)) continue;
      if (square) {
        if (std::count(st.solved.begin(), st.solved.end(), false) > 0)
          return "the subsystem's equations are dependent (one of them follows from the others)";
        continue;  // all solved: nothing left open in square mode (unreachable)
      }
      st.open[i] = false;
      st.branch.checks.push_back(static_cast<int>(i));
    }
    if (std::find(st.solved.begin(), st.solved.end(), false) == st.solved.end()) {
      for (std::size_t i = 0; i < st.equations.size(); ++i)
        if (st.open[i]) st.branch.checks.push_back(static_cast<int>(i));
      std::sort(st.branch.checks.begin(), st.branch.checks.end());
      for (std::size_t u = 0; u < n; ++u) st.branch.values.push_back(GiNaC::normal(st.values[u]));
      out.push_back(st.branch);
      return "";
    }
    // A linear pivot: fewest unknowns, a coefficient free of unknowns, the smaller equation.
    using Key = std::tuple<int, int, std::size_t, std::size_t, std::size_t>;
    std::optional<Key> best;
    for (std::size_t i = 0; i < st.equations.size(); ++i) {
      if (!st.open[i]) continue;
      const GiNaC::ex& e = st.equations[i];
      int count = 0;
      for (std::size_t u = 0; u < n; ++u) count += !st.solved[u] && e.has(unknowns[u]);
      for (std::size_t u = 0; u < n; ++u) {
        if (st.solved[u] || e.degree(unknowns[u]) != 1) continue;
        const GiNaC::ex c = e.coeff(unknowns[u], 1);
        const Key key{count, has_unknown(c, unknowns, st.solved) ? 1 : 0, terms(e), i, u};
        if (!best || key < *best) best = key;
      }
    }
    if (best) {
      const std::size_t i = std::get<3>(*best), u = std::get<4>(*best);
      const GiNaC::ex& e = st.equations[i];
      const GiNaC::ex value = GiNaC::normal(-e.coeff(unknowns[u], 0) / e.coeff(unknowns[u], 1));
      st.open[i] = false;
      st.branch.pivots.push_back(static_cast<int>(i));
      substitute(st, unknowns, u, value);
      continue;
    }
    // A quadratic in one unknown: two branches.
    bool split = false;
    for (std::size_t i = 0; i < st.equations.size() && !split; ++i) {
      if (!st.open[i]) continue;
      const GiNaC::ex& e = st.equations[i];
      std::size_t only = n, count = 0;
      for (std::size_t u = 0; u < n; ++u)
        if (!st.solved[u] && e.has(unknowns[u])) {
          only = u;
          ++count;
        }
      if (count != 1 || e.degree(unknowns[only]) != 2) continue;
      const GiNaC::ex a = e.coeff(unknowns[only], 2), b = e.coeff(unknowns[only], 1), c = e.coeff(unknowns[only], 0);
      const GiNaC::ex root = GiNaC::sqrt(GiNaC::expand(b * b - 4 * a * c));
      for (int sign : {1, -1}) {
        State next = st;
        next.open[i] = false;
        next.branch.pivots.push_back(static_cast<int>(i));
        substitute(next, unknowns, only, (-b + sign * root) / (2 * a));
        stack.push_back(next);
      }
      split = true;
    }
    if (split) return "";
    return "no remaining equation is linear in an unknown or quadratic in a single one";
  }
}

}  // namespace

Elimination eliminate(const std::vector<GiNaC::ex>& equations, const std::vector<GiNaC::symbol>& unknowns, bool square,
                      const EliminationLimits& limits) {
  Elimination result;
  if (square && equations.size() != unknowns.size()) {
    result.failure = "not square";
    return result;
  }
  if (equations.size() < unknowns.size()) {
    result.failure = "fewer equations than unknowns";
    return result;
  }
  State start;
  for (const GiNaC::ex& e : equations) start.equations.push_back(tidy(e, unknowns));
  start.open.assign(equations.size(), true);
  for (const GiNaC::symbol& x : unknowns) start.values.push_back(x);
  start.solved.assign(unknowns.size(), false);
  for (std::size_t i = 0; i < start.equations.size(); ++i)
    if (start.equations[i].is_zero()) {
      if (square) {
        result.failure = "an equation vanishes identically";
        return result;
      }
      start.open[i] = false;
      start.branch.checks.push_back(static_cast<int>(i));
    }
  std::vector<State> stack = {start};
  while (!stack.empty()) {
    State st = std::move(stack.back());
    stack.pop_back();
    const std::string failure = run(std::move(st), unknowns, square, limits, stack, result.branches);
    if (!failure.empty() && result.failure.empty()) result.failure = failure;
  }
  // A branch that failed while another finished: the finished ones stand, and the failure stays noted only when
  // nothing finished.
  if (!result.branches.empty()) result.failure.clear();
  return result;
}

}  // namespace mbgen::elimination
