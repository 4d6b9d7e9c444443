#include "lag_polynomials.hpp"

#include "numerics/polynomial_roots.hpp"

#include <algorithm>
#include <complex>
#include <vector>

namespace mbgen::methods {

using Complex = std::complex<double>;

void divide_by(const Eigen::VectorXd& p, Eigen::VectorXd& x) {
  const Eigen::Index n = p.size();
  for (Eigen::Index k = 1; k < x.size(); ++k) {
    double v = x[k];
    const Eigen::Index m = std::min(n, k);
    for (Eigen::Index l = 1; l <= m; ++l) v -= p[l - 1] * x[k - l];
    x[k] = v;
  }
}

Eigen::VectorXd multiply_by(const Eigen::VectorXd& p, const Eigen::VectorXd& x) {
  const Eigen::Index N = x.size();
  Eigen::VectorXd out = x;
  for (Eigen::Index l = 1; l <= p.size() && l < N; ++l) out.tail(N - l) += p[l - 1] * x.head(N - l);
  return out;
}

Eigen::VectorXd product(const Eigen::VectorXd& p, const Eigen::VectorXd& r) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(p.size() + r.size());
  out.head(p.size()) += p;
  out.head(r.size()) += r;
  for (Eigen::Index i = 0; i < p.size(); ++i)
    for (Eigen::Index j = 0; j < r.size(); ++j) out[i + j + 1] += p[i] * r[j];
  return out;
}

Eigen::VectorXd section(const Sections& S, const Eigen::VectorXd& v, int k) {
  return v.segment(S.offset(k), S.order(k));
}

Eigen::VectorXd polynomial_of(const Sections& S, const Eigen::VectorXd& v, int skip) {
  Eigen::VectorXd p(0);
  for (int k = 0; k < S.count(); ++k)
    if (k != skip) p = product(p, section(S, v, k));
  return p;
}

Eigen::VectorXd sections_of(const Eigen::VectorXd& p) {
  const int n = static_cast<int>(p.size());
  Sections S{n};
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  if (n == 0) return out;
  Eigen::VectorXd ascending(n + 1);  // in z: p_n .. p_1, 1
  ascending[n] = 1;
  for (int l = 1; l <= n; ++l) ascending[n - l] = p[l - 1];
  std::vector<Complex> roots = numerics::polynomial_roots(ascending);
  roots.resize(static_cast<std::size_t>(n), 0.0);  // leading zero coefficients: roots at 0
  std::vector<Complex> pairs;
  std::vector<double> real;
  for (const Complex& z : roots) {
    if (z.imag() > 0) pairs.push_back(z);
    else if (z.imag() == 0) real.push_back(z.real());
  }
  std::sort(real.begin(), real.end());
  int k = 0;
  for (const Complex& z : pairs) {
    if (k >= S.count() || S.order(k) != 2) break;
    out[S.offset(k)] = -2 * z.real();
    out[S.offset(k) + 1] = std::norm(z);
    ++k;
  }
  for (std::size_t i = 0; i < real.size() && k < S.count(); ++k) {
    if (S.order(k) == 2 && i + 1 < real.size()) {
      out[S.offset(k)] = -(real[i] + real[i + 1]);
      out[S.offset(k) + 1] = real[i] * real[i + 1];
      i += 2;
    } else {
      out[S.offset(k)] = -real[i];
      i += 1;
    }
  }
  return out;
}

int reflect(const Sections& S, Eigen::VectorXd& v) {
  int reflected = 0;
  for (int k = 0; k < S.count(); ++k) {
    double* s = v.data() + S.offset(k);
    if (S.order(k) == 1) {
      if (std::abs(s[0]) > 1) {
        s[0] = 1 / s[0];
        ++reflected;
      }
      continue;
    }
    const double disc = s[0] * s[0] - 4 * s[1];
    if (disc < 0) {  // a conjugate pair, |z|^2 = s_1
      if (s[1] > 1) {
        s[0] /= s[1];
        s[1] = 1 / s[1];
        reflected += 2;
      }
      continue;
    }
    double r1 = (-s[0] + std::sqrt(disc)) / 2, r2 = (-s[0] - std::sqrt(disc)) / 2;
    int here = 0;
    if (std::abs(r1) > 1) r1 = 1 / r1, ++here;
    if (std::abs(r2) > 1) r2 = 1 / r2, ++here;
    if (here) {
      s[0] = -(r1 + r2);
      s[1] = r1 * r2;
      reflected += here;
    }
  }
  return reflected;
}

double largest_root(const Eigen::VectorXd& p) {
  const Eigen::Index n = p.size();
  if (n == 0) return 0;
  Eigen::VectorXd ascending(n + 1);
  ascending[n] = 1;
  for (Eigen::Index l = 1; l <= n; ++l) ascending[n - l] = p[l - 1];
  double r = 0;
  for (const Complex& z : numerics::polynomial_roots(ascending)) r = std::max(r, std::abs(z));
  return r;
}

}  // namespace mbgen::methods
