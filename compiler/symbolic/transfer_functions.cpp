#include "symbolic/transfer_functions.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <set>
#include <cstdio>
#include <sstream>

#include "symbolic/geometry.hpp"
#include "symbolic/modular.hpp"
#include "symbolic/pencil_determinants.hpp"
#include "numerics/constants.hpp"
#include "numerics/polynomial_roots.hpp"

namespace mbgen::symbolic {

namespace {

bool touches(const std::vector<int>& block, const GiNaC::matrix& mat, bool column, unsigned index) {
  for (int i : block)
    if (!(column ? mat(i, index) : mat(index, i)).is_zero()) return true;
  return false;
}

// Ascending coefficients of a polynomial in s, divided by `lead`.
std::vector<GiNaC::ex> coefficients(const GiNaC::ex& poly, const GiNaC::symbol& s, const GiNaC::ex& lead,
                                    bool symbolic) {
  if (poly.is_zero()) return {0};
  const int degree = poly.degree(s);
  std::vector<GiNaC::ex> c;
  for (int k = 0; k <= degree; ++k) {
    const GiNaC::ex ck = poly.coeff(s, k) / lead;
    c.push_back(symbolic ? GiNaC::ex(GiNaC::collect_common_factors(GiNaC::normal(ck))) : tidy(ck));
  }
  return c;
}

GiNaC::ex polynomial(const std::vector<GiNaC::ex>& c, const GiNaC::symbol& s) {
  GiNaC::ex p = 0;
  for (size_t k = 0; k < c.size(); ++k) p += c[k] * GiNaC::pow(s, static_cast<int>(k));
  return p;
}

std::string format_number(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// Readable list of the roots of a polynomial in s with numeric coefficients: modes as f/zeta, real roots as s.
std::string describe_roots(const GiNaC::ex& factor, const GiNaC::symbol& s) {
  const int degree = factor.degree(s);
  Eigen::VectorXd c(degree + 1);
  for (int k = 0; k <= degree; ++k) c[k] = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(factor.coeff(s, k))).to_double();
  std::vector<std::complex<double>> sorted = numerics::polynomial_roots(c);
  std::sort(sorted.begin(), sorted.end(),
            [](auto a, auto b) { return std::abs(a) != std::abs(b) ? std::abs(a) < std::abs(b) : a.imag() < b.imag(); });
  std::string text;
  for (const std::complex<double>& r : sorted) {
    if (r.imag() < 0) continue;
    if (!text.empty()) text += ", ";
    if (r.imag() > 1e-9 * std::max(1.0, std::abs(r))) {
      const double wn = std::abs(r);
      const double zeta = -r.real() / wn;
      text += format_number(wn / numerics::kTwoPi) + " Hz (zeta " + format_number(zeta == 0 ? 0.0 : zeta) + ")";
    } else {
      text += "s = " + format_number(r.real());
    }
  }
  return text;
}

std::vector<int> pair_coordinates(const SymbolicModel& sm, int output, int input) {
  const unsigned o = static_cast<unsigned>(output), u = static_cast<unsigned>(input);
  std::vector<int> coordinates;
  for (const std::vector<int>& block : sm.blocks)
    if (touches(block, sm.B, true, u) &&
        (touches(block, sm.Cd, false, o) || touches(block, sm.Cv, false, o) || touches(block, sm.Ca, false, o)))
      coordinates.insert(coordinates.end(), block.begin(), block.end());
  std::sort(coordinates.begin(), coordinates.end());
  return coordinates;
}

// det P of a set of coordinates, shared by every pair on the same blocks (GiNaC route only).
using DeterminantCache = std::map<std::vector<int>, GiNaC::ex>;

// The GiNaC route: determinants of the bordered matrix by GiNaC (minor expansion, exponential in the size), for
// symbolic coefficients (blocks of up to kMaxSymbolicBlockSize) and for exact numbers that are not all rational
// (pi, square roots: the multimodular route needs rationals).
void ginac_transfer_function(const SymbolicModel& sm, TransferFunction& tf, DeterminantCache& cache) {
  const unsigned o = static_cast<unsigned>(tf.output), u = static_cast<unsigned>(tf.input);
  const unsigned n = static_cast<unsigned>(tf.coordinates.size());
  const GiNaC::exmap values = tf.symbolic ? GiNaC::exmap{} : sm.values();
  const GiNaC::ex& s = sm.s;
  // Bordered matrix [[P, b], [c, 0]]: its determinant is -c adj(P) b.
  GiNaC::matrix bordered(n + 1, n + 1);
  for (unsigned r = 0; r < n; ++r) {
    const unsigned i = static_cast<unsigned>(tf.coordinates[r]);
    for (unsigned c = 0; c < n; ++c) {
      const unsigned j = static_cast<unsigned>(tf.coordinates[c]);
      bordered(r, c) = GiNaC::expand((sm.M(i, j) * s * s + sm.C_total(i, j) * s + sm.K(i, j)).subs(values));
    }
    bordered(r, n) = sm.B(i, u).subs(values);
    bordered(n, r) = GiNaC::expand((sm.Cd(o, i) + sm.Cv(o, i) * s + sm.Ca(o, i) * s * s).subs(values));
  }
  auto cached = cache.find(tf.coordinates);
  if (cached == cache.end()) {
    GiNaC::matrix p(n, n);
    for (unsigned r = 0; r < n; ++r)
      for (unsigned c = 0; c < n; ++c) p(r, c) = bordered(r, c);
    cached = cache.emplace(tf.coordinates, GiNaC::expand(p.determinant())).first;
  }
  const GiNaC::ex denominator = cached->second;
  const GiNaC::ex numerator = GiNaC::expand(-bordered.determinant());
  const GiNaC::ex lead = denominator.coeff(s, denominator.degree(s));
  tf.denominator = coefficients(denominator, sm.s, lead, tf.symbolic);
  tf.numerator = coefficients(numerator, sm.s, lead, tf.symbolic);
}

// The exact rational value of a constant expression, if it is one.
bool rational_value(const GiNaC::ex& e, cln::cl_RA& out) {
  if (!GiNaC::is_a<GiNaC::numeric>(e)) return false;
  const GiNaC::numeric& x = GiNaC::ex_to<GiNaC::numeric>(e);
  if (!x.is_rational()) return false;
  out = cln::the<cln::cl_RA>(x.to_cl_N());
  return true;
}

// P(s), the inputs' columns and the outputs' rows on `coordinates` at the current values, if all are rational.
bool rational_pencil(const SymbolicModel& sm, const std::vector<int>& coordinates, const std::vector<int>& outputs,
                     const std::vector<int>& inputs, RationalPencil& rp) {
  const GiNaC::exmap values = sm.values();
  const int n = rp.n = static_cast<int>(coordinates.size());
  const auto N = static_cast<std::size_t>(n);
  rp.M.assign(N * N, 0);
  rp.C.assign(N * N, 0);
  rp.K.assign(N * N, 0);
  auto value = [&](const GiNaC::ex& e, cln::cl_RA& out) { return e.is_zero() || rational_value(tidy(e.subs(values)), out); };
  for (std::size_t r = 0; r < N; ++r)
    for (std::size_t c = 0; c < N; ++c) {
      const unsigned i = static_cast<unsigned>(coordinates[r]), j = static_cast<unsigned>(coordinates[c]);
      if (!value(sm.M(i, j), rp.M[r * N + c]) || !value(sm.C_total(i, j), rp.C[r * N + c]) ||
          !value(sm.K(i, j), rp.K[r * N + c]))
        return false;
    }
  for (int u : inputs) {
    rp.inputs.emplace_back(N, 0);
    for (std::size_t r = 0; r < N; ++r)
      if (!value(sm.B(static_cast<unsigned>(coordinates[r]), static_cast<unsigned>(u)), rp.inputs.back()[r])) return false;
  }
  for (int o : outputs) {
    RationalPencil::OutputRow row{std::vector<cln::cl_RA>(N, 0), std::vector<cln::cl_RA>(N, 0), std::vector<cln::cl_RA>(N, 0)};
    for (std::size_t r = 0; r < N; ++r) {
      const unsigned i = static_cast<unsigned>(coordinates[r]), oo = static_cast<unsigned>(o);
      if (!value(sm.Cd(oo, i), row.d[r]) || !value(sm.Cv(oo, i), row.v[r]) || !value(sm.Ca(oo, i), row.a[r]))
        return false;
    }
    rp.outputs.push_back(std::move(row));
  }
  return true;
}

// Ascending coefficients of an exact polynomial over its denominator's leading coefficient, trailing zeros dropped
// ({0} for zero), as the GiNaC route gives them.
std::vector<GiNaC::ex> normalized(const std::vector<cln::cl_RA>& poly, const cln::cl_RA& lead) {
  std::size_t size = poly.size();
  while (size > 1 && cln::zerop(poly[size - 1])) --size;
  std::vector<GiNaC::ex> c;
  for (std::size_t k = 0; k < size; ++k) c.push_back(GiNaC::numeric(poly[k] / lead));
  return c;
}

std::vector<int> distinct(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

std::optional<Cancellation> probable_cancellation(const SymbolicModel& sm, const TransferFunction& tf,
                                                  const std::vector<ModularPolynomials>& images, std::size_t o,
                                                  std::size_t u);

// The distinct irrational numbers the block's M, C and K hold at the parameters' values (sqrt(2), pi, sin(1/2)). GiNaC's
// exact determinants work in the field they generate, whose degree doubles with each independent square root: the
// cost grows with their number far faster than with the block's size (a 12-mass chain with a distinct square root
// per spring took over 120 s, with three of them 0.1 s; the spinning spindle's 12-coordinate block, with pi alone,
// a fraction of a second).
std::size_t irrational_atoms(const SymbolicModel& sm, const std::vector<int>& coordinates) {
  const GiNaC::exmap values = sm.values();
  std::set<GiNaC::ex, GiNaC::ex_is_less> atoms;
  for (const GiNaC::matrix* m : {&sm.M, &sm.C_total, &sm.K})
    for (int i : coordinates)
      for (int j : coordinates) {
        const GiNaC::ex e = (*m)(static_cast<unsigned>(i), static_cast<unsigned>(j)).subs(values);
        for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it) {
          const bool root = GiNaC::is_a<GiNaC::power>(*it) && GiNaC::is_a<GiNaC::numeric>(it->op(0)) &&
                            !it->op(1).info(GiNaC::info_flags::integer);
          if (root || GiNaC::is_a<GiNaC::constant>(*it) || GiNaC::is_a<GiNaC::function>(*it)) atoms.insert(*it);
        }
      }
  return atoms.size();
}

// The transfer functions of `pairs` (indices into tfs, all on the same coordinates, numeric): exact rationals by
// the multimodular route (pencil_determinants.hpp) when the values are rational and the block is at most
// kMaxExactBlockSize; the GiNaC route for other exact numbers on small blocks; otherwise none (left to run time).
// Without exact coefficients, the pairs' probable cancellations go into `probable` (by index into tfs; one pencil's
// images modulo two primes serve every pair on the same coordinates).
void numeric_transfer_functions(const SymbolicModel& sm, std::vector<TransferFunction>& tfs,
                                const std::vector<std::size_t>& pairs, DeterminantCache& cache,
                                std::map<std::size_t, std::optional<Cancellation>>& probable) {
  const std::vector<int>& coordinates = tfs[pairs.front()].coordinates;
  std::vector<int> outputs, inputs;
  for (std::size_t k : pairs) {
    outputs.push_back(tfs[k].output);
    inputs.push_back(tfs[k].input);
  }
  outputs = distinct(outputs);
  inputs = distinct(inputs);
  RationalPencil rp;
  const bool rational = rational_pencil(sm, coordinates, outputs, inputs, rp);
  const int n = static_cast<int>(coordinates.size());
  if (rational && n <= kMaxExactBlockSize) {
    try {
      const PencilPolynomials p = exact_polynomials(rp);
      std::size_t degree = p.determinant.size() - 1;
      while (degree > 0 && cln::zerop(p.determinant[degree])) --degree;
      const cln::cl_RA lead = p.determinant[degree];
      if (!cln::zerop(lead)) {
        for (std::size_t k : pairs) {
          const auto o = static_cast<std::size_t>(std::find(outputs.begin(), outputs.end(), tfs[k].output) - outputs.begin());
          const auto u = static_cast<std::size_t>(std::find(inputs.begin(), inputs.end(), tfs[k].input) - inputs.begin());
          tfs[k].denominator = normalized(p.determinant, lead);
          tfs[k].numerator = normalized(p.numerators[o][u], lead);
        }
        return;
      }
    } catch (const std::domain_error&) {
      // det P(s) vanishes identically: on a small block the GiNaC route below says so as before.
    }
  }
  // Over the exact limit, or not rational (or a singular pencil) on a block too large, or holding too many irrational
  // numbers, for GiNaC's exponential route: left to run time.
  if (n > kMaxGinacBlockSize || (!rational && irrational_atoms(sm, coordinates) > kMaxIrrationalNumbers)) {
    for (std::size_t k : pairs) tfs[k].exact = false;
    if (rational) {
      const std::vector<ModularPolynomials> images = {modular_polynomials(rp, 0), modular_polynomials(rp, 1)};
      for (std::size_t k : pairs) {
        const auto o = static_cast<std::size_t>(std::find(outputs.begin(), outputs.end(), tfs[k].output) - outputs.begin());
        const auto u = static_cast<std::size_t>(std::find(inputs.begin(), inputs.end(), tfs[k].input) - inputs.begin());
        probable[k] = probable_cancellation(sm, tfs[k], images, o, u);
      }
    }
    return;
  }
  for (std::size_t k : pairs) ginac_transfer_function(sm, tfs[k], cache);
}

// True if the rational polynomials (ascending, leading coefficients non-zero) are proven coprime by their images
// modulo a prime that divides no denominator and neither leading coefficient: the gcd over the rationals then
// reduces to a divisor of the gcd modulo p of the same degree, so degree 0 there means degree 0 here. GiNaC's gcd
// of two degree-200 polynomials with thousand-digit coefficients takes minutes; this takes microseconds, and a
// real cancellation still goes to the exact gcd below.
bool coprime_modulo_a_prime(const std::vector<GiNaC::ex>& num, const std::vector<GiNaC::ex>& den) {
  std::vector<cln::cl_RA> a, b;
  cln::cl_RA x;
  for (const GiNaC::ex& c : num) {
    if (!rational_value(c, x)) return false;
    a.push_back(x);
  }
  for (const GiNaC::ex& c : den) {
    if (!rational_value(c, x)) return false;
    b.push_back(x);
  }
  for (int k = 0; k < 3; ++k) {
    const std::uint64_t p = modular::prime(k);
    const cln::cl_I big_p = static_cast<cln::cl_I>(p);
    bool usable = true;
    auto residues = [&](const std::vector<cln::cl_RA>& poly) {
      std::vector<std::uint64_t> r;
      const modular::Field f(p);
      for (const cln::cl_RA& c : poly) {
        const cln::cl_I d = cln::mod(cln::denominator(c), big_p);
        if (cln::zerop(d)) {
          usable = false;
          return r;
        }
        r.push_back(f.to_plain(f.mul(f.from_integer(cln::numerator(c)), f.inverse(f.from_integer(d)))));
      }
      if (r.back() == 0) usable = false;  // p divides the leading coefficient
      return r;
    };
    const std::vector<std::uint64_t> ra = residues(a), rb = residues(b);
    if (usable) return gcd_degree_modulo(ra, rb, p) == 0;
  }
  return false;
}

// For a transfer function without exact coefficients (a block too large): the numerator and denominator modulo two
// primes (`images`, of a pencil with the pair's output `o` and input `u` among its own). Coprime modulo one that
// keeps the denominator's full degree proves there is no cancellation; a common factor modulo both is reported as
// probable (its exact form is not computed).
std::optional<Cancellation> probable_cancellation(const SymbolicModel& sm, const TransferFunction& tf,
                                                  const std::vector<ModularPolynomials>& images, std::size_t o,
                                                  std::size_t u) {
  int common = -1, full_degree = -1;
  std::vector<std::pair<int, int>> found;  // (denominator degree, gcd degree) per usable prime
  for (const ModularPolynomials& m : images) {
    if (!m.ok) continue;
    std::vector<std::uint64_t> den = m.determinant;
    while (!den.empty() && den.back() == 0) den.pop_back();
    const std::vector<std::uint64_t>& num = m.numerators[o][u];
    if (std::all_of(num.begin(), num.end(), [](std::uint64_t v) { return v == 0; })) return std::nullopt;
    found.emplace_back(static_cast<int>(den.size()) - 1, gcd_degree_modulo(num, den, m.prime));
    full_degree = std::max(full_degree, found.back().first);
  }
  for (const auto& [degree, gcd] : found) {
    if (degree == full_degree && gcd == 0) return std::nullopt;
    common = common < 0 ? gcd : std::min(common, gcd);
  }
  if (found.size() < 2 || common <= 0) return std::nullopt;
  Cancellation c;
  c.output = tf.output;
  c.input = tf.input;
  c.common_factor = 0;
  c.text = sm.model->outputs[tf.output].name + "/" + sm.model->inputs[tf.input].name +
           ": numerator and denominator probably share a factor of degree " + std::to_string(common) +
           " at the current parameter values (they do modulo two primes; the block of " +
           std::to_string(tf.coordinates.size()) + " coordinates is too large for exact coefficients), so " +
           std::to_string(common) + " poles probably cancel and do not show in this transfer function";
  return c;
}

// Fills tf's coordinates, and the transfer function itself when it is zero (no coordinate links the pair) or small
// enough to be symbolic. False when it needs the numeric route (numeric_transfer_functions).
bool zero_or_symbolic(const SymbolicModel& sm, TransferFunction& tf, DeterminantCache& cache) {
  tf.coordinates = pair_coordinates(sm, tf.output, tf.input);
  if (tf.coordinates.empty()) {
    tf.symbolic = true;
    tf.numerator = {0};
    tf.denominator = {1};
    return true;
  }
  if (static_cast<int>(tf.coordinates.size()) > kMaxSymbolicBlockSize) return false;
  tf.symbolic = true;
  ginac_transfer_function(sm, tf, cache);
  return true;
}

}  // namespace

TransferFunction transfer_function(const SymbolicModel& sm, int output, int input) {
  std::vector<TransferFunction> tfs(1);
  TransferFunction& tf = tfs.front();
  tf.output = output;
  tf.input = input;
  DeterminantCache cache;
  if (!zero_or_symbolic(sm, tf, cache)) {
    std::map<std::size_t, std::optional<Cancellation>> probable;
    numeric_transfer_functions(sm, tfs, {0}, cache, probable);
  }
  return tf;
}

std::optional<Cancellation> find_cancellation(const SymbolicModel& sm, const TransferFunction& tf) {
  if (!tf.exact) {
    RationalPencil rp;
    if (!rational_pencil(sm, tf.coordinates, {tf.output}, {tf.input}, rp)) return std::nullopt;
    return probable_cancellation(sm, tf, {modular_polynomials(rp, 0), modular_polynomials(rp, 1)}, 0, 0);
  }
  const GiNaC::exmap values = sm.values();
  std::vector<GiNaC::ex> num, den;
  for (const GiNaC::ex& c : tf.numerator) num.push_back(tidy(c.subs(values)));
  for (const GiNaC::ex& c : tf.denominator) den.push_back(tidy(c.subs(values)));
  GiNaC::ex numerator = polynomial(num, sm.s), denominator = polynomial(den, sm.s);
  if (numerator.is_zero() || denominator.degree(sm.s) == 0) return std::nullopt;
  if (coprime_modulo_a_prime(num, den)) return std::nullopt;
  // gcd works on polynomials over the rationals: stand-in symbols for pi, square roots etc., shared by both
  // polynomials, and the constant denominators (1/pi, say, from a mass of pi) multiplied out; neither moves a root.
  GiNaC::exmap stand_ins;
  numerator = numerator.to_rational(stand_ins).numer();
  denominator = denominator.to_rational(stand_ins).numer();
  GiNaC::ex common = GiNaC::gcd(GiNaC::expand(numerator), GiNaC::expand(denominator));
  if (common.degree(sm.s) <= 0) return std::nullopt;
  common = GiNaC::expand(common.subs(stand_ins));  // stand_ins maps each stand-in symbol to what it replaced
  common = tidy(GiNaC::collect(GiNaC::expand(common / common.coeff(sm.s, common.degree(sm.s))), sm.s));
  Cancellation c;
  c.output = tf.output;
  c.input = tf.input;
  c.common_factor = common;
  const ir::ModelIr& model = *sm.model;
  std::string factor_text;
  {
    std::ostringstream os;
    os << common;
    factor_text = os.str();
  }
  c.text = model.outputs[tf.output].name + "/" + model.inputs[tf.input].name +
           ": numerator and denominator share the factor (" + factor_text +
           ") at the current parameter values, so the poles " + describe_roots(common, sm.s) +
           " cancel and do not show in this transfer function";
  return c;
}

void add_transfer_functions(SymbolicModel& sm) {
  sm.transfer_functions.clear();
  sm.cancellations.clear();
  DeterminantCache cache;
  // Numeric pairs are grouped by their coordinates: one pencil's determinants serve them all.
  std::map<std::vector<int>, std::vector<std::size_t>> numeric;
  for (size_t o = 0; o < sm.model->outputs.size(); ++o)
    for (size_t u = 0; u < sm.model->inputs.size(); ++u) {
      TransferFunction tf;
      tf.output = static_cast<int>(o);
      tf.input = static_cast<int>(u);
      if (!zero_or_symbolic(sm, tf, cache)) numeric[tf.coordinates].push_back(sm.transfer_functions.size());
      sm.transfer_functions.push_back(std::move(tf));
    }
  std::map<std::size_t, std::optional<Cancellation>> probable;
  for (const auto& [coordinates, pairs] : numeric)
    numeric_transfer_functions(sm, sm.transfer_functions, pairs, cache, probable);
  for (std::size_t k = 0; k < sm.transfer_functions.size(); ++k) {
    const TransferFunction& tf = sm.transfer_functions[k];
    auto c = tf.exact ? find_cancellation(sm, tf) : probable[k];
    if (c) sm.cancellations.push_back(*c);
  }
}

}  // namespace mbgen::symbolic
