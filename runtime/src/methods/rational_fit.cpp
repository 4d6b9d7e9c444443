#include "rational_fit.hpp"

#include "numerics/levenberg_marquardt.hpp"
#include "numerics/polynomial_roots.hpp"
#include "polynomial.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>

#include <cmath>
#include <complex>
#include <stdexcept>

namespace mbgen::methods {

namespace {

using Complex = std::complex<double>;

// The layout of the scaled coefficient vector x = [a_0 .. a_{q-1}, b_{0,0} .. b_{0,d0}, b_{1,0} ..].
struct Layout {
  int q = 0;
  std::vector<Eigen::Index> offset;  // of each channel's numerator
  Eigen::Index size = 0;
  explicit Layout(int order, const std::vector<RationalChannel>& channels) : q(order) {
    size = q;
    for (const auto& c : channels) {
      offset.push_back(size);
      size += c.numerator_degree + 1;
    }
  }
};

Eigen::VectorXd denominator_of(const Eigen::VectorXd& x, int q) {
  Eigen::VectorXd d(q + 1);
  d.head(q) = x.head(q);
  d[q] = 1;
  return d;
}

// Reflects roots with a positive real part into the left half-plane; returns how many.
int reflect_unstable(Eigen::VectorXd& x, int q) {
  std::vector<Complex> roots = numerics::polynomial_roots(denominator_of(x, q));
  int flipped = 0;
  for (auto& r : roots)
    if (r.real() > 0) {
      r = Complex(-r.real(), r.imag());
      ++flipped;
    }
  if (flipped) x.head(q) = poly_from_roots(roots).head(q).real();
  return flipped;
}

}  // namespace

IdentifiedTf fit_rational_frf(const Eigen::VectorXd& omega, const std::vector<RationalChannel>& channels,
                              const std::string& input, int order, double omega0, RationalFitReport* report) {
  // A caller's bug: not invalid_argument, which the callers take for data that cannot serve.
  if (order < 1 || channels.empty() || !(omega0 > 0)) throw std::logic_error("fit_rational_frf: bad arguments");
  const Layout layout(order, channels);
  const int q = order;
  const Eigen::Index lines = omega.size();
  const Eigen::Index rows = 2 * lines * static_cast<Eigen::Index>(channels.size());
  if (rows <= layout.size)
    throw std::invalid_argument("a rational fit of order " + std::to_string(q) + " needs more than " +
                                std::to_string(layout.size) + " real equations; the data hold " + std::to_string(rows));
  std::vector<Complex> s(static_cast<std::size_t>(lines));
  for (Eigen::Index k = 0; k < lines; ++k) s[static_cast<std::size_t>(k)] = Complex(0, omega[k] / omega0);
  // Powers s^j, j = 0 .. q, per line.
  Eigen::MatrixXcd pw(lines, q + 1);
  for (Eigen::Index k = 0; k < lines; ++k) {
    pw(k, 0) = 1;
    for (int j = 1; j <= q; ++j) pw(k, j) = pw(k, j - 1) * s[static_cast<std::size_t>(k)];
  }

  RationalFitReport rep;
  // Sanathanan-Koerner, from Levy's fit (D_prev = 1).
  Eigen::VectorXd x = Eigen::VectorXd::Zero(layout.size);
  Eigen::VectorXcd dprev = Eigen::VectorXcd::Ones(lines);
  for (int it = 0; it < 50; ++it) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, layout.size);
    Eigen::VectorXd rhs(rows);
    Eigen::Index row = 0;
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const RationalChannel& ch = channels[c];
      for (Eigen::Index k = 0; k < lines; ++k) {
        const Complex w = 1.0 / (dprev[k] * ch.sigma[k]);
        const Complex h = ch.H[k] * w;
        Eigen::VectorXcd a(layout.size);
        a.setZero();
        for (int i = 0; i < q; ++i) a[i] = pw(k, i) * h;
        for (int j = 0; j <= ch.numerator_degree; ++j) a[layout.offset[c] + j] = -pw(k, j) * w;
        const Complex b = -pw(k, q) * h;
        A.row(row) = a.real().transpose();
        rhs[row++] = b.real();
        A.row(row) = a.imag().transpose();
        rhs[row++] = b.imag();
      }
    }
    Eigen::VectorXd norms = A.colwise().norm().transpose();
    for (Eigen::Index j = 0; j < norms.size(); ++j)
      if (!(norms[j] > 0)) norms[j] = 1;
    const Eigen::VectorXd y = (A * norms.cwiseInverse().asDiagonal()).colPivHouseholderQr().solve(rhs);
    Eigen::VectorXd next = y.cwiseQuotient(norms);
    rep.reflected_poles += reflect_unstable(next, q);
    const double change = (next.head(q) - x.head(q)).norm() / std::max(next.head(q).norm(), 1e-300);
    x = next;
    rep.sk_iterations = it + 1;
    for (Eigen::Index k = 0; k < lines; ++k) dprev[k] = poly_eval(denominator_of(x, q), s[static_cast<std::size_t>(k)]);
    if (change < 1e-10) break;
  }

  // Levenberg-Marquardt on the weighted output error.
  const estimation::ResidualFunction f = [&](const Eigen::VectorXd& p, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    r.resize(rows);
    if (J) J->setZero(rows, layout.size);
    const Eigen::VectorXd d = denominator_of(p, q);
    Eigen::Index row = 0;
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const RationalChannel& ch = channels[c];
      const Eigen::VectorXd num = p.segment(layout.offset[c], ch.numerator_degree + 1);
      for (Eigen::Index k = 0; k < lines; ++k) {
        const Complex sk = s[static_cast<std::size_t>(k)];
        const Complex den = poly_eval(d, sk);
        if (std::abs(den) == 0) return false;
        const double w = 1 / ch.sigma[k];
        const Complex g = poly_eval(num, sk) / den;
        const Complex e = (g - ch.H[k]) * w;
        r[row] = e.real();
        r[row + 1] = e.imag();
        if (J) {
          for (int i = 0; i < q; ++i) {
            const Complex v = -g * pw(k, i) / den * w;
            (*J)(row, i) = v.real();
            (*J)(row + 1, i) = v.imag();
          }
          for (int j = 0; j <= ch.numerator_degree; ++j) {
            const Complex v = pw(k, j) / den * w;
            (*J)(row, layout.offset[c] + j) = v.real();
            (*J)(row + 1, layout.offset[c] + j) = v.imag();
          }
        }
        row += 2;
      }
    }
    return true;
  };
  // LM works on x / |x_SK| (every unknown starts at +-1), so that its step tolerance is relative.
  Eigen::VectorXd unit = x.cwiseAbs();
  for (Eigen::Index j = 0; j < unit.size(); ++j)
    if (!(unit[j] > 0)) unit[j] = 1;
  const estimation::ResidualFunction g = [&](const Eigen::VectorXd& z, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    if (!f(z.cwiseProduct(unit), r, J)) return false;
    if (J) *J = *J * unit.asDiagonal();
    return true;
  };
  estimation::LmOptions lm;
  lm.max_iterations = 500;
  const estimation::LmResult fit = estimation::levenberg_marquardt(g, x.cwiseQuotient(unit), lm);
  x = fit.x.cwiseProduct(unit);
  rep.lm_iterations = fit.iterations;
  rep.converged = fit.converged;

  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  if (!f(x, r, &J)) throw std::invalid_argument("the rational fit has a pole on the frequency axis");
  rep.cost = r.squaredNorm();
  rep.residual_count = static_cast<long>(rows);
  double measured = 0;
  for (const auto& ch : channels) measured += ch.H.cwiseAbs2().cwiseQuotient(ch.sigma.cwiseAbs2()).sum();
  rep.nrmse = measured > 0 ? std::sqrt(rep.cost / measured) : 0;

  // Covariance of the scaled coefficients, then of the physical ones: a_i = x_i w0^(q-i), b_j = x_j w0^(q-j).
  const double s2 = rep.cost / double(rows - layout.size);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  Eigen::VectorXd inv2 = Eigen::VectorXd::Zero(sv.size());
  for (Eigen::Index i = 0; i < sv.size(); ++i)
    if (sv[i] > sv[0] * 1e-14) inv2[i] = 1 / (sv[i] * sv[i]);
  const Eigen::MatrixXd cov_scaled = s2 * svd.matrixV() * inv2.asDiagonal() * svd.matrixV().transpose();
  Eigen::VectorXd unscale(layout.size);
  for (int i = 0; i < q; ++i) unscale[i] = std::pow(omega0, q - i);
  for (std::size_t c = 0; c < channels.size(); ++c)
    for (int j = 0; j <= channels[c].numerator_degree; ++j) unscale[layout.offset[c] + j] = std::pow(omega0, q - j);

  IdentifiedTf tf;
  tf.input = input;
  tf.denominator = denominator_of(x, q);
  tf.denominator.head(q) = tf.denominator.head(q).cwiseProduct(unscale.head(q));
  for (std::size_t c = 0; c < channels.size(); ++c) {
    tf.outputs.push_back(channels[c].output);
    const Eigen::Index n = channels[c].numerator_degree + 1;
    tf.numerators.push_back(x.segment(layout.offset[c], n).cwiseProduct(unscale.segment(layout.offset[c], n)));
  }
  tf.covariance = unscale.asDiagonal() * cov_scaled * unscale.asDiagonal();
  tf.covariance_note = "linearised maximum-likelihood covariance of the rational fit, s^2 (J^T J)^-1";
  if (report) *report = rep;
  return tf;
}

}  // namespace mbgen::methods
