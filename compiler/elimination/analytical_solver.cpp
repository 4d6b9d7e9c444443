#include "elimination/analytical_solver.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "emit/infix_printer.hpp"
#include "elimination/elimination.hpp"
#include "symbolic/transfer_functions.hpp"

namespace mbgen::elimination {

namespace {

// Deterministic text. GiNaC orders operands by hash values, which follow addresses and so differ from run to run: its
// own printer gave the two-step's method_details in another order on each run of the same binary, and the
// elimination's results themselves came out in different but equal forms (a sign moved between numerator and
// denominator). So: the reduced fraction, numerator and denominator expanded, the sign fixed by the denominator's
// term whose monomial prints first, each printed by infix_text.
std::string text(const GiNaC::ex& e) {
  const GiNaC::ex nd = GiNaC::normal(e).numer_denom();
  GiNaC::ex numerator = GiNaC::expand(nd.op(0)), denominator = GiNaC::expand(nd.op(1));
  if (denominator.is_equal(GiNaC::ex(1))) return emit::infix_text(numerator);
  // The sign: the denominator's term whose monomial (the term without its numeric factor) prints first is positive.
  const auto coefficient = [](const GiNaC::ex& term) {
    if (GiNaC::is_a<GiNaC::numeric>(term)) return GiNaC::ex_to<GiNaC::numeric>(term);
    if (GiNaC::is_a<GiNaC::mul>(term) && GiNaC::is_a<GiNaC::numeric>(term.op(term.nops() - 1)))
      return GiNaC::ex_to<GiNaC::numeric>(term.op(term.nops() - 1));
    return GiNaC::numeric(1);
  };
  std::string first_monomial;
  bool negative = false;
  const std::size_t count = GiNaC::is_a<GiNaC::add>(denominator) ? denominator.nops() : 1;
  for (std::size_t k = 0; k < count; ++k) {
    const GiNaC::ex term = count == 1 ? denominator : denominator.op(k);
    const GiNaC::numeric c = coefficient(term);
    const std::string monomial = emit::infix_text(term / c);
    if (k == 0 || monomial < first_monomial) {
      first_monomial = monomial;
      negative = c.is_negative();
    }
  }
  if (negative) {
    numerator = GiNaC::expand(-numerator);
    denominator = GiNaC::expand(-denominator);
  }
  return "(" + emit::infix_text(numerator) + ")/(" + emit::infix_text(denominator) + ")";
}

// For the report: a closed form or an exact value, shortened past `limit` characters.
std::string shortened(std::string t, std::size_t limit) {
  if (t.size() > limit) t = t.substr(0, limit) + "... (" + std::to_string(t.size()) + " characters)";
  return t;
}

std::string coefficient_name(const CoefficientSystem& system, const CoefficientSystem::Equation& eq,
                             const symbolic::SymbolicModel& sm) {
  std::string name = eq.channel < 0 ? "a" + std::to_string(eq.power)
                                    : "b" + std::to_string(eq.power) + "_" +
                                          sm.model->outputs[static_cast<std::size_t>(
                                              system.tfs[eq.tf].outputs[static_cast<std::size_t>(eq.channel)])].name;
  if (system.tfs.size() > 1) name = "T" + std::to_string(eq.tf + 1) + "_" + name;
  return name;
}

// Number of ways to choose k of n, saturating above `cap`.
std::size_t choose(std::size_t n, std::size_t k, std::size_t cap) {
  double c = 1;
  for (std::size_t i = 0; i < k; ++i) {
    c = c * double(n - i) / double(i + 1);
    if (c > double(cap)) return cap + 1;
  }
  return static_cast<std::size_t>(std::llround(c));
}

// The real values of one branch at the identified coefficients, or nothing (complex, or a division by zero).
bool real_values(const std::vector<GiNaC::ex>& forms, const GiNaC::exmap& data, std::vector<GiNaC::ex>& out) {
  out.clear();
  for (const GiNaC::ex& f : forms) {
    GiNaC::ex v;
    try {
      v = GiNaC::normal(f.subs(data));
    } catch (const std::exception&) {
      return false;  // a pole of the closed form: this branch does not apply to these data
    }
    const GiNaC::ex approx = GiNaC::evalf(v);
    if (!GiNaC::is_a<GiNaC::numeric>(approx)) return false;
    const GiNaC::numeric x = GiNaC::ex_to<GiNaC::numeric>(approx);
    if (!x.is_real()) {
      // Rounding of nested radicals can leave an imaginary part far below the real one.
      if (std::abs(x.imag().to_double()) > 1e-12 * std::abs(x.real().to_double())) return false;
      v = GiNaC::real_part(v);
    }
    out.push_back(v);
  }
  return true;
}

}  // namespace

GiNaC::numeric exact(double x) {
  if (x == 0 || !std::isfinite(x)) return 0;
  int e = 0;
  const double m = std::frexp(x, &e);  // x = m 2^e, 0.5 <= |m| < 1
  const auto mantissa = static_cast<long long>(std::ldexp(m, 53));
  const GiNaC::numeric two(2);
  return GiNaC::numeric(mantissa) * two.power(e - 53);
}

ExactSolution solve_exactly(const symbolic::SymbolicModel& sm, const CoefficientSystem& system,
                            const std::vector<GiNaC::numeric>& identified) {
  ExactSolution out;
  const std::size_t m = system.equations.size(), n = system.unknowns.size();
  if (identified.size() != m) throw std::invalid_argument("solve_exactly: one identified value per equation");
  for (const auto& eq : system.equations) out.coefficients.emplace_back(coefficient_name(system, eq, sm));
  if (n > kMaxUnknowns) {
    out.unavailable = std::to_string(n) + " unknowns, above the " + std::to_string(kMaxUnknowns) +
                      " for which a closed form is attempted";
    return out;
  }
  // Model parameter index -> symbolic parameter.
  if (static_cast<Eigen::Index>(sm.parameters.size()) != system.values.size())
    throw std::invalid_argument("solve_exactly: the values do not match the model's parameters");
  std::vector<GiNaC::symbol> unknowns;
  for (int p : system.unknowns) unknowns.push_back(sm.parameters[static_cast<std::size_t>(p)].sym);

  // Per transfer function: the model's coefficients with the known parameters substituted.
  std::vector<GiNaC::ex> equations(m);
  std::vector<std::vector<GiNaC::ex>> denominators(system.tfs.size());
  std::vector<std::vector<std::vector<GiNaC::ex>>> numerators(system.tfs.size());
  for (std::size_t t = 0; t < system.tfs.size(); ++t) {
    const CoefficientSystem::TransferFunction& tf = system.tfs[t];
    GiNaC::exmap known, at_values;
    for (std::size_t p = 0; p < sm.parameters.size(); ++p) {
      double v = system.values[static_cast<Eigen::Index>(p)];
      bool overridden = false;
      for (const auto& [idx, value] : tf.overrides)
        if (static_cast<std::size_t>(idx) == p) {
          v = value;
          overridden = true;
        }
      const bool unknown =
          !overridden && std::find(system.unknowns.begin(), system.unknowns.end(), static_cast<int>(p)) != system.unknowns.end();
      if (!unknown) known[sm.parameters[p].sym] = exact(v);
      at_values[sm.parameters[p].sym] = exact(v);
    }
    for (std::size_t c = 0; c < tf.outputs.size(); ++c) {
      const symbolic::TransferFunction g = symbolic::transfer_function(sm, tf.outputs[c], tf.input);
      if (!g.exact || !g.symbolic) {
        out.unavailable = "the transfer functions from " + sm.model->inputs[static_cast<std::size_t>(tf.input)].name +
                          " live on a block of " + std::to_string(g.coordinates.size()) +
                          " coordinates, above the " + std::to_string(symbolic::kMaxSymbolicBlockSize) +
                          " for which the compiler derives their coefficients as expressions";
        return out;
      }
      if (static_cast<int>(g.denominator.size()) - 1 != tf.order) {
        out.unavailable = "the symbolic transfer function has order " + std::to_string(g.denominator.size() - 1) +
                          ", the compared one " + std::to_string(tf.order);
        return out;
      }
      if (c == 0) denominators[t] = g.denominator;
      else
        for (std::size_t k = 0; k < g.denominator.size(); ++k)
          if (!GiNaC::normal(g.denominator[k] - denominators[t][k]).is_zero()) {
            out.unavailable = "the outputs of " + tf.file + " see different blocks (no common denominator)";
            return out;
          }
      numerators[t].push_back(g.numerator);
    }
    for (std::size_t i = 0; i < m; ++i) {
      const CoefficientSystem::Equation& eq = system.equations[i];
      if (eq.tf != t) continue;
      const std::vector<GiNaC::ex>& poly =
          eq.channel < 0 ? denominators[t] : numerators[t][static_cast<std::size_t>(eq.channel)];
      const GiNaC::ex model = eq.power < static_cast<int>(poly.size()) ? poly[static_cast<std::size_t>(eq.power)] : GiNaC::ex(0);
      // The symbolic coefficient must be the runtime's (same block, same normalisation).
      const double here = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(model.subs(at_values))).to_double();
      if (!(std::abs(here - eq.model_at_prior) <= 1e-9 * std::max(std::abs(eq.model_at_prior), 1e-300))) {
        out.unavailable = "the symbolic coefficient " + text(out.coefficients[i]) + " (" + std::to_string(here) +
                          ") is not the runtime's (" + std::to_string(eq.model_at_prior) + ")";
        return out;
      }
      equations[i] = model.subs(known) - out.coefficients[i];
    }
  }

  GiNaC::exmap data;
  for (std::size_t i = 0; i < m; ++i) data[out.coefficients[i]] = identified[i];
  auto record = [&](const Elimination& e, const std::vector<int>& fallback_equations) {
    ExactSubsystem sub;
    sub.failure = e.failure;
    sub.equations = fallback_equations;
    if (!e.branches.empty()) {
      if (fallback_equations.empty()) {
        sub.equations = e.branches.front().pivots;
        std::sort(sub.equations.begin(), sub.equations.end());
      }
      sub.closed_form = e.branches.front().values;
    }
    for (const EliminationBranch& b : e.branches) {
      sub.all_forms.push_back(b.values);
      std::vector<GiNaC::ex> values;
      if (real_values(b.values, data, values)) sub.solutions.push_back(values);
    }
    if (sub.failure.empty() && sub.solutions.empty()) sub.failure = "no real solution at the identified coefficients";
    out.subsystems.push_back(sub);
  };
  if (choose(m, n, kMaxSubsystems) <= kMaxSubsystems) {
    out.subsystem_choice = "every choice of " + std::to_string(n) + " of the " + std::to_string(m) +
                           " equations, each solved exactly (square elimination)";
    std::vector<int> pick(n);
    for (std::size_t k = 0; k < n; ++k) pick[k] = static_cast<int>(k);
    for (;;) {
      std::vector<GiNaC::ex> eqs;
      for (int i : pick) eqs.push_back(equations[static_cast<std::size_t>(i)]);
      record(eliminate(eqs, unknowns, true), pick);
      // Next combination in lexicographic order.
      std::size_t k = n;
      while (k > 0 && pick[k - 1] == static_cast<int>(m - n + k - 1)) --k;
      if (k == 0) break;
      ++pick[k - 1];
      for (std::size_t j = k; j < n; ++j) pick[j] = pick[j - 1] + 1;
    }
  } else {
    out.subsystem_choice = "one greedy elimination over all " + std::to_string(m) +
                           " equations (too many square subsystems to try each); the equations it does not use are "
                           "the checks";
    const Elimination e = eliminate(equations, unknowns, false);
    // Branches may pivot on different equations: one subsystem per distinct set.
    std::map<std::vector<int>, Elimination> by_pivots;
    for (const EliminationBranch& b : e.branches) {
      std::vector<int> key = b.pivots;
      std::sort(key.begin(), key.end());
      by_pivots[key].branches.push_back(b);
    }
    if (by_pivots.empty()) record(e, {});
    for (const auto& [key, sub] : by_pivots) record(sub, key);
  }
  return out;
}

AnalyticalSolver make_analytical_solver(std::shared_ptr<const symbolic::SymbolicModel> sm) {
  return [sm](const CoefficientSystem& system) {
    std::vector<GiNaC::numeric> identified;
    for (const auto& eq : system.equations) identified.push_back(exact(eq.identified));
    const ExactSolution exact_solution = solve_exactly(*sm, system, identified);
    AnalyticalSolution out;
    out.unavailable = exact_solution.unavailable;
    out.subsystem_choice = exact_solution.subsystem_choice;
    for (const GiNaC::symbol& s : exact_solution.coefficients) out.coefficient_names.push_back(s.get_name());
    for (const ExactSubsystem& e : exact_solution.subsystems) {
      AnalyticalSubsystem sub;
      sub.equations = e.equations;
      sub.failure = e.failure;
      for (std::size_t u = 0; u < system.unknowns.size() && u < e.closed_form.size(); ++u) {
        std::string form = sm->parameters[static_cast<std::size_t>(system.unknowns[u])].name + " = ";
        for (std::size_t b = 0; b < e.all_forms.size(); ++b) form += (b ? "  |  " : "") + shortened(text(e.all_forms[b][u]), 1000);
        sub.closed_form.push_back(form);
      }
      for (const std::vector<GiNaC::ex>& s : e.solutions) {
        Eigen::VectorXd v = system.values;
        std::vector<std::string> texts;
        for (std::size_t u = 0; u < s.size(); ++u) {
          v[system.unknowns[u]] = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(s[u])).to_double();
          // Exact rationals of data read as doubles run to hundreds of digits.
          texts.push_back(shortened(text(s[u]), 200));
        }
        sub.solutions.push_back(v);
        sub.exact.push_back(texts);
      }
      out.subsystems.push_back(sub);
    }
    return out;
  };
}

}  // namespace mbgen::elimination
