#include "symbolic/transfer_functions.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <cstdio>
#include <sstream>

#include "symbolic/geometry.hpp"

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
  std::vector<double> c;
  for (int k = 0; k <= degree; ++k) c.push_back(GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(factor.coeff(s, k))).to_double());
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
  for (int k = 0; k < degree; ++k) {
    companion(0, k) = -c[degree - 1 - k] / c[degree];
    if (k + 1 < degree) companion(k + 1, k) = 1;
  }
  const Eigen::VectorXcd roots = companion.eigenvalues();
  std::vector<std::complex<double>> sorted(roots.data(), roots.data() + roots.size());
  std::sort(sorted.begin(), sorted.end(),
            [](auto a, auto b) { return std::abs(a) != std::abs(b) ? std::abs(a) < std::abs(b) : a.imag() < b.imag(); });
  std::string text;
  for (const std::complex<double>& r : sorted) {
    if (r.imag() < 0) continue;
    if (!text.empty()) text += ", ";
    if (r.imag() > 1e-9 * std::max(1.0, std::abs(r))) {
      const double wn = std::abs(r);
      const double zeta = -r.real() / wn;
      text += format_number(wn / (2 * M_PI)) + " Hz (zeta " + format_number(zeta == 0 ? 0.0 : zeta) + ")";
    } else {
      text += "s = " + format_number(r.real());
    }
  }
  return text;
}

// det P of a set of coordinates, shared by every pair on the same blocks (the costly part for large blocks).
using DeterminantCache = std::map<std::vector<int>, GiNaC::ex>;

TransferFunction transfer_function(const SymbolicModel& sm, int output, int input, DeterminantCache& cache) {
  TransferFunction tf;
  tf.output = output;
  tf.input = input;
  const unsigned o = static_cast<unsigned>(output), u = static_cast<unsigned>(input);
  for (const std::vector<int>& block : sm.blocks)
    if (touches(block, sm.B, true, u) &&
        (touches(block, sm.Cd, false, o) || touches(block, sm.Cv, false, o) || touches(block, sm.Ca, false, o)))
      tf.coordinates.insert(tf.coordinates.end(), block.begin(), block.end());
  std::sort(tf.coordinates.begin(), tf.coordinates.end());
  if (tf.coordinates.empty()) {
    tf.symbolic = true;
    tf.numerator = {0};
    tf.denominator = {1};
    return tf;
  }
  const unsigned n = static_cast<unsigned>(tf.coordinates.size());
  tf.symbolic = static_cast<int>(n) <= kMaxSymbolicBlockSize;
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
  return tf;
}

}  // namespace

TransferFunction transfer_function(const SymbolicModel& sm, int output, int input) {
  DeterminantCache cache;
  return transfer_function(sm, output, input, cache);
}

std::optional<Cancellation> find_cancellation(const SymbolicModel& sm, const TransferFunction& tf) {
  const GiNaC::exmap values = sm.values();
  std::vector<GiNaC::ex> num, den;
  for (const GiNaC::ex& c : tf.numerator) num.push_back(tidy(c.subs(values)));
  for (const GiNaC::ex& c : tf.denominator) den.push_back(tidy(c.subs(values)));
  GiNaC::ex numerator = polynomial(num, sm.s), denominator = polynomial(den, sm.s);
  if (numerator.is_zero() || denominator.degree(sm.s) == 0) return std::nullopt;
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
  const ir::Model& model = *sm.model;
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
  for (size_t o = 0; o < sm.model->outputs.size(); ++o)
    for (size_t u = 0; u < sm.model->inputs.size(); ++u) {
      sm.transfer_functions.push_back(transfer_function(sm, static_cast<int>(o), static_cast<int>(u), cache));
      if (auto c = find_cancellation(sm, sm.transfer_functions.back())) sm.cancellations.push_back(*c);
    }
}

}  // namespace mbgen::symbolic
