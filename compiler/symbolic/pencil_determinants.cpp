#include "symbolic/pencil_determinants.hpp"

#include <cln/integer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "symbolic/modular.hpp"

namespace mbgen::symbolic {

namespace {

using modular::Field;
using u64 = std::uint64_t;

// The pencil scaled to integers, renumbered, in band storage: entry (i, j), |i - j| within the band, of row i
// is at i * width + (j - i + lower).
struct IntegerPencil {
  int n = 0, lower = 0, upper = 0, width = 1;
  std::vector<int> order;  // new index -> original index
  std::vector<cln::cl_I> M, C, K;
  std::vector<std::vector<cln::cl_I>> b;                 // [input][new index]
  std::vector<std::array<std::vector<cln::cl_I>, 3>> c;  // [output][d, v, a][new index]
  std::vector<cln::cl_I> row_scale;                      // per original row: the lcm of its denominators
  std::vector<cln::cl_I> output_scale;
  double bound_bits = 0;  // log2 of a bound on every coefficient of every determinant
};

cln::cl_I lcm_of_denominators(const std::vector<const cln::cl_RA*>& values) {
  cln::cl_I l = 1;
  for (const cln::cl_RA* v : values) l = cln::lcm(l, cln::denominator(*v));
  return l;
}

cln::cl_I scaled(const cln::cl_RA& v, const cln::cl_I& scale) {
  return cln::exquo(scale, cln::denominator(v)) * cln::numerator(v);
}

// Lower and upper bandwidth of a sparsity pattern under a renumbering (order: new -> old).
std::pair<int, int> bandwidths(const std::vector<std::vector<int>>& pattern, const std::vector<int>& order) {
  std::vector<int> position(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) position[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
  int lower = 0, upper = 0;
  for (std::size_t i = 0; i < pattern.size(); ++i)
    for (int j : pattern[i]) {
      const int d = position[i] - position[static_cast<std::size_t>(j)];
      lower = std::max(lower, d);
      upper = std::max(upper, -d);
    }
  return {lower, upper};
}

// Reverse Cuthill-McKee on the symmetrized pattern: breadth-first from a vertex of least degree, neighbours by
// increasing degree, each component in turn, reversed.
std::vector<int> reverse_cuthill_mckee(const std::vector<std::vector<int>>& pattern) {
  const int n = static_cast<int>(pattern.size());
  std::vector<std::vector<int>> adjacent(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int j : pattern[static_cast<std::size_t>(i)])
      if (j != i) {
        adjacent[static_cast<std::size_t>(i)].push_back(j);
        adjacent[static_cast<std::size_t>(j)].push_back(i);
      }
  for (auto& a : adjacent) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  auto degree = [&](int i) { return adjacent[static_cast<std::size_t>(i)].size(); };
  std::vector<int> order;
  std::vector<char> seen(static_cast<std::size_t>(n), 0);
  while (static_cast<int>(order.size()) < n) {
    int start = -1;
    for (int i = 0; i < n; ++i)
      if (!seen[static_cast<std::size_t>(i)] && (start < 0 || degree(i) < degree(start))) start = i;
    seen[static_cast<std::size_t>(start)] = 1;
    for (std::size_t head = order.size(), tail = (order.push_back(start), order.size()); head < tail;
         ++head, tail = order.size()) {
      std::vector<int> next;
      for (int j : adjacent[static_cast<std::size_t>(order[head])])
        if (!seen[static_cast<std::size_t>(j)]) {
          seen[static_cast<std::size_t>(j)] = 1;
          next.push_back(j);
        }
      std::stable_sort(next.begin(), next.end(), [&](int a, int b) { return degree(a) < degree(b); });
      order.insert(order.end(), next.begin(), next.end());
    }
  }
  std::reverse(order.begin(), order.end());
  return order;
}

IntegerPencil to_integers(const RationalPencil& rp) {
  IntegerPencil ip;
  const int n = ip.n = rp.n;
  const auto N = static_cast<std::size_t>(n);
  auto at = [n](int i, int j) { return static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j); };
  std::vector<std::vector<int>> pattern(N);
  ip.row_scale.resize(N);
  for (int i = 0; i < n; ++i) {
    std::vector<const cln::cl_RA*> row;
    for (int j = 0; j < n; ++j) {
      const std::size_t k = at(i, j);
      if (cln::zerop(rp.M[k]) && cln::zerop(rp.C[k]) && cln::zerop(rp.K[k])) continue;
      pattern[static_cast<std::size_t>(i)].push_back(j);
      row.insert(row.end(), {&rp.M[k], &rp.C[k], &rp.K[k]});
    }
    for (const auto& b : rp.inputs) row.push_back(&b[static_cast<std::size_t>(i)]);
    ip.row_scale[static_cast<std::size_t>(i)] = lcm_of_denominators(row);
  }
  std::vector<int> identity(N);
  std::iota(identity.begin(), identity.end(), 0);
  const std::vector<int> rcm = reverse_cuthill_mckee(pattern);
  const auto [l0, u0] = bandwidths(pattern, identity);
  const auto [l1, u1] = bandwidths(pattern, rcm);
  const bool use_rcm = static_cast<long>(l1 + 1) * (u1 + 1) < static_cast<long>(l0 + 1) * (u0 + 1);
  ip.order = use_rcm ? rcm : identity;
  ip.lower = use_rcm ? l1 : l0;
  ip.upper = use_rcm ? u1 : u0;
  ip.width = ip.lower + ip.upper + 1;
  std::vector<int> position(N);
  for (int k = 0; k < n; ++k) position[static_cast<std::size_t>(ip.order[static_cast<std::size_t>(k)])] = k;

  const std::size_t band = N * static_cast<std::size_t>(ip.width);
  ip.M.assign(band, 0);
  ip.C.assign(band, 0);
  ip.K.assign(band, 0);
  ip.b.assign(rp.inputs.size(), std::vector<cln::cl_I>(N, 0));
  std::vector<cln::cl_I> row_max(N, 0);
  for (int i = 0; i < n; ++i) {
    const cln::cl_I& scale = ip.row_scale[static_cast<std::size_t>(i)];
    const int r = position[static_cast<std::size_t>(i)];
    cln::cl_I& largest = row_max[static_cast<std::size_t>(r)];
    for (int j : pattern[static_cast<std::size_t>(i)]) {
      const std::size_t k = at(i, j);
      const std::size_t slot = static_cast<std::size_t>(r) * static_cast<std::size_t>(ip.width) +
                               static_cast<std::size_t>(position[static_cast<std::size_t>(j)] - r + ip.lower);
      ip.M[slot] = scaled(rp.M[k], scale);
      ip.C[slot] = scaled(rp.C[k], scale);
      ip.K[slot] = scaled(rp.K[k], scale);
      largest = cln::max(largest, cln::abs(ip.M[slot]) + cln::abs(ip.C[slot]) + cln::abs(ip.K[slot]));
    }
    for (std::size_t u = 0; u < rp.inputs.size(); ++u) {
      ip.b[u][static_cast<std::size_t>(r)] = scaled(rp.inputs[u][static_cast<std::size_t>(i)], scale);
      largest = cln::max(largest, cln::abs(ip.b[u][static_cast<std::size_t>(r)]));
    }
    // Hadamard: |det| <= prod of row norms; on |s| = 1 each entry of P is at most |M| + |C| + |K|, and a row
    // norm is at most sqrt(entries) times its largest entry.
    ip.bound_bits += static_cast<double>(cln::integer_length(largest)) +
                     0.5 * std::log2(static_cast<double>(pattern[static_cast<std::size_t>(i)].size() + 1));
  }
  cln::cl_I output_max = 0;
  for (const auto& o : rp.outputs) {
    std::vector<const cln::cl_RA*> row;
    for (const auto* part : {&o.d, &o.v, &o.a})
      for (const cln::cl_RA& v : *part) row.push_back(&v);
    const cln::cl_I scale = lcm_of_denominators(row);
    ip.output_scale.push_back(scale);
    std::array<std::vector<cln::cl_I>, 3> c;
    int p = 0;
    for (const auto* part : {&o.d, &o.v, &o.a}) {
      c[static_cast<std::size_t>(p)].assign(N, 0);
      for (int i = 0; i < n; ++i)
        c[static_cast<std::size_t>(p)][static_cast<std::size_t>(position[static_cast<std::size_t>(i)])] =
            scaled((*part)[static_cast<std::size_t>(i)], scale);
      ++p;
    }
    for (int i = 0; i < n; ++i)
      output_max = cln::max(output_max, cln::abs(c[0][static_cast<std::size_t>(i)]) +
                                            cln::abs(c[1][static_cast<std::size_t>(i)]) +
                                            cln::abs(c[2][static_cast<std::size_t>(i)]));
    ip.c.push_back(std::move(c));
  }
  if (!rp.outputs.empty())
    ip.bound_bits += static_cast<double>(cln::integer_length(output_max)) + 0.5 * std::log2(static_cast<double>(n));
  return ip;
}

// One prime's work: the pencil reduced modulo p, evaluated and factored at each point.
class ModularEvaluator {
 public:
  ModularEvaluator(const IntegerPencil& ip, const Field& f) : ip_(ip), f_(f) {
    auto reduce = [&](const std::vector<cln::cl_I>& v) {
      std::vector<u64> r(v.size());
      for (std::size_t k = 0; k < v.size(); ++k) r[k] = cln::zerop(v[k]) ? 0 : f.from_integer(v[k]);
      return r;
    };
    M_ = reduce(ip.M);
    C_ = reduce(ip.C);
    K_ = reduce(ip.K);
    for (const auto& b : ip.b) b_.push_back(reduce(b));
    for (const auto& c : ip.c) c_.push_back({reduce(c[0]), reduce(c[1]), reduce(c[2])});
    a_.resize(M_.size());
    inverse_pivot_.resize(static_cast<std::size_t>(ip.n));
    x_.resize(static_cast<std::size_t>(ip.n));
  }

  // det P(s) and the numerators det P(s) c_o(s) P(s)^-1 b_u at s (Montgomery form); false if P(s) is singular
  // modulo p (then the point is unusable).
  bool evaluate(u64 s, u64& det, std::vector<std::vector<u64>>& numerators) {
    const u64 s2 = f_.mul(s, s);
    for (std::size_t k = 0; k < a_.size(); ++k) a_[k] = f_.add(f_.add(f_.mul(M_[k], s2), f_.mul(C_[k], s)), K_[k]);
    if (!factor_band(det)) return evaluate_dense(s, det, numerators);
    for (std::size_t u = 0; u < b_.size(); ++u) {
      solve_band(b_[u]);
      for (std::size_t o = 0; o < c_.size(); ++o) numerators[o][u] = f_.mul(det, output(o, s, s2));
    }
    return true;
  }

 private:
  u64& band(int i, int j) {
    return a_[static_cast<std::size_t>(i) * static_cast<std::size_t>(ip_.width) + static_cast<std::size_t>(j - i + ip_.lower)];
  }

  u64 output(std::size_t o, u64 s, u64 s2) const {
    u64 y = 0;
    for (std::size_t i = 0; i < x_.size(); ++i) {
      if (x_[i] == 0) continue;
      const u64 ci = f_.add(f_.add(c_[o][0][i], f_.mul(c_[o][1][i], s)), f_.mul(c_[o][2][i], s2));
      y = f_.add(y, f_.mul(ci, x_[i]));
    }
    return y;
  }

  // LU without pivoting in the band (L's multipliers below the diagonal, U on and above).
  bool factor_band(u64& det) {
    const int n = ip_.n;
    det = f_.one();
    for (int k = 0; k < n; ++k) {
      const u64 pivot = band(k, k);
      if (pivot == 0) return false;
      det = f_.mul(det, pivot);
      const u64 inv = f_.inverse(pivot);
      inverse_pivot_[static_cast<std::size_t>(k)] = inv;
      const int last_row = std::min(n - 1, k + ip_.lower), last_col = std::min(n - 1, k + ip_.upper);
      for (int i = k + 1; i <= last_row; ++i) {
        u64& lik = band(i, k);
        if (lik == 0) continue;
        lik = f_.mul(lik, inv);
        const u64 l = lik;
        u64* row_i = &band(i, k + 1);
        const u64* row_k = &band(k, k + 1);
        for (int j = 0; j < last_col - k; ++j) row_i[j] = f_.sub(row_i[j], f_.mul(l, row_k[j]));
      }
    }
    return true;
  }

  void solve_band(const std::vector<u64>& b) {
    const int n = ip_.n;
    for (int i = 0; i < n; ++i) {
      u64 v = b[static_cast<std::size_t>(i)];
      for (int k = std::max(0, i - ip_.lower); k < i; ++k) v = f_.sub(v, f_.mul(band(i, k), x_[static_cast<std::size_t>(k)]));
      x_[static_cast<std::size_t>(i)] = v;
    }
    for (int i = n - 1; i >= 0; --i) {
      u64 v = x_[static_cast<std::size_t>(i)];
      for (int j = i + 1; j <= std::min(n - 1, i + ip_.upper); ++j)
        v = f_.sub(v, f_.mul(band(i, j), x_[static_cast<std::size_t>(j)]));
      x_[static_cast<std::size_t>(i)] = f_.mul(v, inverse_pivot_[static_cast<std::size_t>(i)]);
    }
  }

  // The rare point where the band elimination meets a zero pivot: dense elimination with row pivoting.
  bool evaluate_dense(u64 s, u64& det, std::vector<std::vector<u64>>& numerators) {
    const int n = ip_.n;
    const auto N = static_cast<std::size_t>(n);
    const u64 s2 = f_.mul(s, s);
    const std::size_t rhs = b_.size();
    std::vector<u64> a(N * (N + rhs), 0);  // [P | b_0 ... b_{m-1}]
    const std::size_t stride = N + rhs;
    for (int i = 0; i < n; ++i) {
      for (int j = std::max(0, i - ip_.lower); j <= std::min(n - 1, i + ip_.upper); ++j) {
        const std::size_t k = static_cast<std::size_t>(i) * static_cast<std::size_t>(ip_.width) +
                              static_cast<std::size_t>(j - i + ip_.lower);
        a[static_cast<std::size_t>(i) * stride + static_cast<std::size_t>(j)] =
            f_.add(f_.add(f_.mul(M_[k], s2), f_.mul(C_[k], s)), K_[k]);
      }
      for (std::size_t u = 0; u < rhs; ++u) a[static_cast<std::size_t>(i) * stride + N + u] = b_[u][static_cast<std::size_t>(i)];
    }
    det = f_.one();
    for (std::size_t k = 0; k < N; ++k) {
      std::size_t p = k;
      while (p < N && a[p * stride + k] == 0) ++p;
      if (p == N) return false;
      if (p != k) {
        for (std::size_t j = 0; j < stride; ++j) std::swap(a[p * stride + j], a[k * stride + j]);
        det = f_.sub(0, det);
      }
      det = f_.mul(det, a[k * stride + k]);
      const u64 inv = f_.inverse(a[k * stride + k]);
      for (std::size_t j = k; j < stride; ++j) a[k * stride + j] = f_.mul(a[k * stride + j], inv);
      for (std::size_t i = 0; i < N; ++i) {
        if (i == k || a[i * stride + k] == 0) continue;
        const u64 l = a[i * stride + k];
        for (std::size_t j = k; j < stride; ++j) a[i * stride + j] = f_.sub(a[i * stride + j], f_.mul(l, a[k * stride + j]));
      }
    }
    for (std::size_t u = 0; u < rhs; ++u) {
      for (std::size_t i = 0; i < N; ++i) x_[i] = a[i * stride + N + u];
      for (std::size_t o = 0; o < c_.size(); ++o) numerators[o][u] = f_.mul(det, output(o, s, s2));
    }
    return true;
  }

  const IntegerPencil& ip_;
  const Field& f_;
  std::vector<u64> M_, C_, K_, a_, inverse_pivot_, x_;
  std::vector<std::vector<u64>> b_;
  std::vector<std::array<std::vector<u64>, 3>> c_;
};

// Coefficients (Montgomery form, ascending) of the polynomial of degree <= d taking `values` at offset, offset + 1,
// ..., offset + d: Newton's divided differences (the spacing is 1, so level j divides by j), then expanded.
std::vector<u64> interpolate(std::vector<u64> v, u64 offset, const Field& f, const std::vector<u64>& inverse) {
  const std::size_t d = v.size() - 1;
  for (std::size_t j = 1; j <= d; ++j)
    for (std::size_t i = d; i >= j; --i) v[i] = f.mul(f.sub(v[i], v[i - 1]), inverse[j]);
  std::vector<u64> c(d + 1, 0);
  c[0] = v[d];
  for (std::size_t k = d; k-- > 0;) {
    const u64 xk = f.from_small(offset + k);
    for (std::size_t t = d - k; t >= 1; --t) c[t] = f.sub(c[t - 1], f.mul(xk, c[t]));
    c[0] = f.sub(v[k], f.mul(xk, c[0]));
  }
  return c;
}

// All polynomials modulo one prime (plain residues), at points offset, ..., offset + 2n; false if P is singular
// modulo p at one of them.
bool polynomials_modulo(const IntegerPencil& ip, const Field& f, u64 offset, std::vector<u64>& det,
                        std::vector<std::vector<std::vector<u64>>>& numerators) {
  const std::size_t points = 2 * static_cast<std::size_t>(ip.n) + 1, outputs = ip.c.size(), inputs = ip.b.size();
  ModularEvaluator evaluator(ip, f);
  std::vector<u64> det_values(points);
  std::vector<std::vector<std::vector<u64>>> num_values(outputs, std::vector<std::vector<u64>>(inputs, std::vector<u64>(points)));
  std::vector<std::vector<u64>> at(outputs, std::vector<u64>(inputs));
  for (std::size_t k = 0; k < points; ++k) {
    if (!evaluator.evaluate(f.from_small(offset + k), det_values[k], at)) return false;
    for (std::size_t o = 0; o < outputs; ++o)
      for (std::size_t u = 0; u < inputs; ++u) num_values[o][u][k] = at[o][u];
  }
  std::vector<u64> inverse(points);
  for (std::size_t j = 1; j < points; ++j) inverse[j] = f.inverse(f.from_small(j));
  auto plain = [&](std::vector<u64> c) {
    for (u64& x : c) x = f.to_plain(x);
    return c;
  };
  det = plain(interpolate(det_values, offset, f, inverse));
  numerators.assign(outputs, std::vector<std::vector<u64>>(inputs));
  for (std::size_t o = 0; o < outputs; ++o)
    for (std::size_t u = 0; u < inputs; ++u) numerators[o][u] = plain(interpolate(num_values[o][u], offset, f, inverse));
  return true;
}

// Evaluation points: s = 1, ..., 2n + 1 first; if P is singular modulo the prime at one of them (a root of det P
// modulo p, or of det P itself), another run of points further out.
constexpr int kOffsetTries = 4;
u64 offset_of_try(int t, int n) { return 1 + static_cast<u64>(t) * (1000003 + 2 * static_cast<u64>(n)); }

}  // namespace

PencilPolynomials exact_polynomials(const RationalPencil& rp) {
  const IntegerPencil ip = to_integers(rp);
  const int primes = static_cast<int>(std::floor((ip.bound_bits + 2) / 61.99)) + 2;
  const std::size_t points = 2 * static_cast<std::size_t>(ip.n) + 1, outputs = ip.c.size(), inputs = ip.b.size();
  // residues[polynomial][coefficient][prime]; polynomial 0 is det P, then the numerators output-major.
  std::vector<std::vector<std::vector<u64>>> residues(1 + outputs * inputs,
                                                      std::vector<std::vector<u64>>(points, std::vector<u64>(static_cast<std::size_t>(primes))));
  int offset_try = 0;
  for (int k = 0; k < primes; ++k) {
    const Field f(modular::prime(k));
    std::vector<u64> det;
    std::vector<std::vector<std::vector<u64>>> num;
    while (!polynomials_modulo(ip, f, offset_of_try(offset_try, ip.n), det, num))
      if (++offset_try == kOffsetTries) throw std::domain_error("exact_polynomials: P(s) is singular");
    for (std::size_t c = 0; c < points; ++c) {
      residues[0][c][static_cast<std::size_t>(k)] = det[c];
      for (std::size_t o = 0; o < outputs; ++o)
        for (std::size_t u = 0; u < inputs; ++u) residues[1 + o * inputs + u][c][static_cast<std::size_t>(k)] = num[o][u][c];
    }
  }
  const modular::Reconstructor crt(primes);
  cln::cl_I det_scale = 1;
  for (const cln::cl_I& d : ip.row_scale) det_scale = det_scale * d;
  PencilPolynomials result;
  for (std::size_t c = 0; c < points; ++c) result.determinant.push_back(crt(residues[0][c]) / det_scale);
  result.numerators.assign(outputs, std::vector<std::vector<cln::cl_RA>>(inputs));
  for (std::size_t o = 0; o < outputs; ++o)
    for (std::size_t u = 0; u < inputs; ++u)
      for (std::size_t c = 0; c < points; ++c)
        result.numerators[o][u].push_back(crt(residues[1 + o * inputs + u][c]) / (det_scale * ip.output_scale[o]));
  return result;
}

ModularPolynomials modular_polynomials(const RationalPencil& rp, int prime_index) {
  const IntegerPencil ip = to_integers(rp);
  ModularPolynomials m;
  m.prime = modular::prime(prime_index);
  const cln::cl_I p = static_cast<cln::cl_I>(m.prime);
  for (const auto* scales : {&ip.row_scale, &ip.output_scale})
    for (const cln::cl_I& d : *scales)
      if (cln::zerop(cln::mod(d, p))) return m;
  const Field f(m.prime);
  for (int t = 0; t < kOffsetTries; ++t)
    if (polynomials_modulo(ip, f, offset_of_try(t, ip.n), m.determinant, m.numerators)) {
      m.ok = true;
      return m;
    }
  return m;
}

int gcd_degree_modulo(std::vector<u64> a, std::vector<u64> b, u64 p) {
  const Field f(p);
  auto trim = [](std::vector<u64>& v) {
    while (!v.empty() && v.back() == 0) v.pop_back();
  };
  for (u64& x : a) x = f.from_small(x % p);
  for (u64& x : b) x = f.from_small(x % p);
  trim(a);
  trim(b);
  while (!b.empty()) {
    // a <- a mod b
    const u64 inv = f.inverse(b.back());
    while (a.size() >= b.size()) {
      const u64 q = f.mul(a.back(), inv);
      const std::size_t shift = a.size() - b.size();
      for (std::size_t i = 0; i < b.size(); ++i) a[shift + i] = f.sub(a[shift + i], f.mul(q, b[i]));
      a.pop_back();  // its coefficient is now zero
      trim(a);
    }
    std::swap(a, b);
  }
  return static_cast<int>(a.size()) - 1;
}

}  // namespace mbgen::symbolic
