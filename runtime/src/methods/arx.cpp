#include "arx.hpp"

#include "numerics/polynomial_roots.hpp"
#include "polynomial.hpp"
#include "numerics/constants.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mbgen::methods {

namespace {

using Complex = std::complex<double>;

double rms(const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / double(std::max<Eigen::Index>(v.size(), 1))); }

// Columns of the regressor matrix: per lag l (0 only with a first-order hold), a_l (l >= 1) then b_{o,l} per output.
struct ArxLayout {
  int outputs = 0, first_lag = 1;
  long columns(int n) const { return long(n) * (1 + outputs) + (first_lag == 0 ? outputs : 0); }
  long a_column(int l) const { return (first_lag == 0 ? outputs : 0) + long(l - 1) * (1 + outputs); }
  long b_column(int o, int l) const { return l == 0 ? o : a_column(l) + 1 + o; }
};

// Response x_k of x' = lambda x + u under the record's hold, from rest: x_{k+1} = E x_k + G0 u_k + G1 u_{k+1}.
Eigen::VectorXcd pole_response(Complex lambda, const Eigen::VectorXd& u, double dt, bool foh) {
  const Complex E = std::exp(lambda * dt);
  Complex g0, g1 = 0;
  if (!foh) {
    g0 = (E - 1.0) / lambda;
  } else {
    g0 = E / lambda - (E - 1.0) / (lambda * lambda * dt);
    g1 = (E - 1.0) / lambda - g0;
  }
  Eigen::VectorXcd x(u.size());
  Complex state = 0;
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    x[k] = state;
    state = E * state + g0 * u[k] + (k + 1 < u.size() ? g1 * u[k + 1] : Complex(0));
  }
  return x;
}

// Each pole's response to the record's input: the regressors 2 Re x and -2 Im x of Re r and Im r.
Eigen::MatrixXd pole_regressors(const std::vector<Complex>& poles, const Eigen::VectorXd& u, double dt, bool foh) {
  Eigen::MatrixXd Psi(u.size(), 2 * static_cast<Eigen::Index>(poles.size()));
  for (std::size_t k = 0; k < poles.size(); ++k) {
    const Eigen::VectorXcd x = pole_response(poles[k], u, dt, foh);
    Psi.col(2 * static_cast<Eigen::Index>(k)) = 2 * x.real();
    Psi.col(2 * static_cast<Eigen::Index>(k) + 1) = -2 * x.imag();
  }
  return Psi;
}

// The continuous-time transfer function of the given poles (one per pair) with each output's residues fitted to
// the record by least squares, constrained to the model's relative degree; with each numerator's covariance given
// the poles, s^2 (Psi_Z^T Psi_Z)^-1 mapped to the coefficients.
struct NumeratorFit {
  Eigen::VectorXd denominator;
  std::vector<Eigen::VectorXd> numerators;
  std::vector<Eigen::MatrixXd> covariance;  // per output
  double rss_w = 0, yy_w = 0;               // weighted by each output's RMS
};

NumeratorFit fit_numerators(const std::vector<Complex>& poles, const Eigen::VectorXd& u,
                            const std::vector<Eigen::VectorXd>& y, const std::vector<double>& sy, double dt, bool foh,
                            int q, const std::vector<int>& numerator_degree) {
  const int order = 2 * static_cast<int>(poles.size());
  const ModalPolynomials mp = modal_polynomials(poles);
  const Eigen::MatrixXd& T = mp.residue_map;
  const Eigen::MatrixXd Psi = pole_regressors(poles, u, dt, foh);
  NumeratorFit out;
  out.denominator = mp.denominator;
  for (std::size_t o = 0; o < y.size(); ++o) {
    // The model's relative degree q - d kept at the identified order.
    const int d = std::max(order - (q - numerator_degree[o]), 0);
    // Residues constrained so that the coefficients above degree d vanish: rho = Z xi, Z spanning the null space.
    Eigen::MatrixXd Z;
    if (d + 1 < order) {
      const Eigen::MatrixXd high = T.bottomRows(order - d - 1);
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(high, Eigen::ComputeFullV);
      const Eigen::VectorXd sv = svd.singularValues();
      Eigen::Index rank = 0;
      for (Eigen::Index i = 0; i < sv.size(); ++i)
        if (sv[i] > sv[0] * 1e-12) ++rank;
      Z = svd.matrixV().rightCols(T.cols() - rank);
    } else {
      Z = Eigen::MatrixXd::Identity(T.cols(), T.cols());
    }
    const Eigen::VectorXd& yo = y[o];
    const Eigen::MatrixXd PZ = Psi * Z;
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(PZ);
    const Eigen::VectorXd xi = qr.solve(yo);
    const Eigen::MatrixXd map = (T * Z).topRows(d + 1);
    out.numerators.push_back(map * xi);
    const double rss = (yo - PZ * xi).squaredNorm();
    const double s2 = rss / double(std::max<Eigen::Index>(yo.size() - xi.size(), 1));
    const Eigen::MatrixXd info_inv = (PZ.transpose() * PZ).completeOrthogonalDecomposition().pseudoInverse();
    out.covariance.push_back(s2 * map * info_inv * map.transpose());
    const double w = 1 / (sy[o] * sy[o]);
    out.rss_w += rss * w;
    out.yy_w += yo.squaredNorm() * w;
  }
  return out;
}

Eigen::VectorXd stacked_coefficients(const NumeratorFit& f) {
  Eigen::Index size = f.denominator.size() - 1;
  for (const auto& n : f.numerators) size += n.size();
  Eigen::VectorXd v(size);
  v.head(f.denominator.size() - 1) = f.denominator.head(f.denominator.size() - 1);
  Eigen::Index k = f.denominator.size() - 1;
  for (const auto& n : f.numerators) {
    v.segment(k, n.size()) = n;
    k += n.size();
  }
  return v;
}

}  // namespace

ArxIdentification identify_arx(const Eigen::VectorXd& u, const std::vector<Eigen::VectorXd>& y,
                               const std::vector<std::string>& outputs, const std::string& input, double dt,
                               bool first_order_hold, int q, const std::vector<int>& numerator_degree,
                               const ArxOptions& options) {
  const int O = static_cast<int>(y.size());
  const Eigen::Index N = u.size();
  if (O == 0 || q < 2 || q % 2 || static_cast<int>(numerator_degree.size()) != O)
    throw std::logic_error("identify_arx: bad arguments");  // a caller's bug (fit_rational_frf), not the data's
  ArxLayout layout;
  layout.outputs = O;
  layout.first_lag = first_order_hold ? 0 : 1;
  // The highest order: at most max_order, and at least 20 equations per coefficient.
  int n_max = std::max(options.max_order, q);
  while (n_max > q && double(O) * double(N - n_max) < 20.0 * double(layout.columns(n_max))) --n_max;
  if (double(O) * double(N - n_max) < 20.0 * double(layout.columns(n_max)))
    throw std::invalid_argument("the record's " + std::to_string(N) + " samples are too few for an ARX model of order " +
                                std::to_string(q) + " (at least 20 equations per coefficient)");

  // Regressors on normalised signals (each output by its RMS, the input by its RMS).
  const double su = rms(u) > 0 ? rms(u) : 1.0;
  std::vector<double> sy(static_cast<std::size_t>(O));
  for (int o = 0; o < O; ++o) sy[static_cast<std::size_t>(o)] = rms(y[static_cast<std::size_t>(o)]) > 0 ? rms(y[static_cast<std::size_t>(o)]) : 1.0;
  const Eigen::Index per = N - n_max;
  const Eigen::Index R = per * O;
  const long P = layout.columns(n_max);
  // The QR of [Phi | target] in blocks of rows (memory bounded by the block, whatever the record's length): the
  // triangular factor of the rows so far stacked over the next block is factored again. Its last column holds
  // Q^T target (first P entries) and keeps the target's norm.
  constexpr Eigen::Index kBlock = 4096;
  Eigen::MatrixXd top(0, P + 1);
  std::vector<Eigen::VectorXd> yn;
  for (int o = 0; o < O; ++o) yn.push_back(y[static_cast<std::size_t>(o)] / sy[static_cast<std::size_t>(o)]);
  for (Eigen::Index start = 0; start < R; start += kBlock) {
    const Eigen::Index rows = std::min(kBlock, R - start);
    Eigen::MatrixXd block = Eigen::MatrixXd::Zero(top.rows() + rows, P + 1);
    block.topRows(top.rows()) = top;
    for (Eigen::Index i = 0; i < rows; ++i) {
      const Eigen::Index row = start + i;
      const int o = static_cast<int>(row / per);
      const Eigen::Index k = n_max + row % per;
      const Eigen::VectorXd& yo = yn[static_cast<std::size_t>(o)];
      const Eigen::Index r = top.rows() + i;
      block(r, P) = yo[k];
      for (int l = layout.first_lag; l <= n_max; ++l) {
        if (l >= 1) block(r, layout.a_column(l)) = -yo[k - l];
        block(r, layout.b_column(o, l)) = u[k - l] / su;
      }
    }
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(block);
    const Eigen::Index keep = std::min<Eigen::Index>(block.rows(), P + 1);
    top = qr.matrixQR().topRows(keep).triangularView<Eigen::Upper>();
  }
  const Eigen::VectorXd qty = top.col(P).head(P);
  const double yy = top.col(P).squaredNorm();
  const Eigen::MatrixXd Rfactor = top.topLeftCorner(P, P);

  ArxIdentification out;
  out.samples = static_cast<long>(N);
  const double Rn = double(R);
  double best = std::numeric_limits<double>::infinity();
  for (int n = q; n <= n_max; ++n) {
    ArxOrder row;
    row.order = n;
    row.parameters = layout.columns(n);
    const double p = double(row.parameters);
    row.rss = std::max(yy - qty.head(row.parameters).squaredNorm(), yy * 1e-300);
    row.aic = Rn * std::log(row.rss / Rn) + 2 * p;
    row.bic = Rn * std::log(row.rss / Rn) + p * std::log(Rn);
    row.fpe = row.rss / Rn * (Rn + p) / (Rn - p);
    const double c = options.criterion == "bic" ? row.bic : options.criterion == "fpe" ? row.fpe : row.aic;
    if (c < best) {
      best = c;
      out.selected_order = n;
    }
    out.orders.push_back(row);
  }
  const int n = out.selected_order;
  const long p = layout.columns(n);
  const Eigen::VectorXd theta =
      Rfactor.topLeftCorner(p, p).triangularView<Eigen::Upper>().solve(qty.head(p));

  // A(z) = z^n + a_1 z^(n-1) + ... + a_n and B_o(z) = sum_l b_{o,l} z^(n-l), ascending, in physical units.
  Eigen::VectorXd A = Eigen::VectorXd::Zero(n + 1);
  A[n] = 1;
  for (int l = 1; l <= n; ++l) A[n - l] = theta[layout.a_column(l)];
  std::vector<Eigen::VectorXd> B(static_cast<std::size_t>(O), Eigen::VectorXd::Zero(n + 1));
  for (int o = 0; o < O; ++o)
    for (int l = layout.first_lag; l <= n; ++l)
      B[static_cast<std::size_t>(o)][n - l] = theta[layout.b_column(o, l)] * sy[static_cast<std::size_t>(o)] / su;
  prune_and_fit_residues(A, B, u, y, outputs, input, dt, first_order_hold, q, numerator_degree, options, out);
  out.tf.covariance_note =
      "not available: ARX is biased under output noise, and the pruning and the residue fit have no joint "
      "linearisation; a covariance from the least squares would understate the error";
  return out;
}

void prune_and_fit_residues(const Eigen::VectorXd& A, const std::vector<Eigen::VectorXd>& B, const Eigen::VectorXd& u,
                            const std::vector<Eigen::VectorXd>& y, const std::vector<std::string>& outputs,
                            const std::string& input, double dt, bool first_order_hold, int q,
                            const std::vector<int>& numerator_degree, const ArxOptions& options,
                            ArxIdentification& out, const PoleCovariance& pole_covariance) {
  const int O = static_cast<int>(y.size());
  const Eigen::Index N = u.size();
  const int n = static_cast<int>(A.size()) - 1;
  std::vector<double> sy(static_cast<std::size_t>(O));
  for (int o = 0; o < O; ++o) sy[static_cast<std::size_t>(o)] = rms(y[static_cast<std::size_t>(o)]) > 0 ? rms(y[static_cast<std::size_t>(o)]) : 1.0;
  Eigen::VectorXd dA = Eigen::VectorXd::Zero(n);
  for (int k = 1; k <= n; ++k) dA[k - 1] = k * A[k];
  std::vector<std::vector<Complex>> zeros(static_cast<std::size_t>(O));
  for (int o = 0; o < O; ++o) {
    Eigen::VectorXd b = B[static_cast<std::size_t>(o)];
    if (first_order_hold) b -= b[n] * A;  // the strictly proper part (the direct term has no zeros of interest)
    for (const Complex& zz : numerics::polynomial_roots(b))
      if (std::abs(zz) > 0) zeros[static_cast<std::size_t>(o)].push_back(std::log(zz) / dt);
  }

  // Poles, mapped and judged.
  const double nyquist_band = options.band_fraction / dt;  // Hz
  std::vector<ArxPole> poles;
  std::vector<Eigen::VectorXd> peak;  // per pole: per channel |r| / |Re lambda|
  for (const Complex& z : numerics::polynomial_roots(A)) {
    if (z.imag() < 0) continue;
    ArxPole pole;
    const Complex lambda = std::log(z) / dt;
    pole.lambda = lambda;
    pole.f_hz = std::abs(lambda) / numerics::kTwoPi;
    pole.zeta = std::abs(lambda) > 0 ? -lambda.real() / std::abs(lambda) : 1.0;
    Eigen::VectorXd h(O);
    pole.nearest_zero = std::numeric_limits<double>::infinity();
    bool cancelled_everywhere = true;
    for (int o = 0; o < O; ++o) {
      const Complex rho = poly_eval(B[static_cast<std::size_t>(o)], z) / poly_eval(dA, z);
      Complex r;
      if (!first_order_hold) {
        r = rho * lambda / (z - 1.0);
      } else {
        const Complex E = z;
        const Complex g0 = E / lambda - (E - 1.0) / (lambda * lambda * dt), g1 = (E - 1.0) / lambda - g0;
        r = rho / (g0 + g1 * z);
      }
      h[o] = std::abs(r) / std::max(std::abs(lambda.real()), 1e-300);
      double nearest = std::numeric_limits<double>::infinity();
      for (const Complex& zs : zeros[static_cast<std::size_t>(o)])
        nearest = std::min({nearest, std::abs(zs - lambda), std::abs(zs - std::conj(lambda))});
      nearest /= std::max(std::abs(lambda.real()), 1e-300);
      pole.nearest_zero = std::min(pole.nearest_zero, nearest);
      if (!(nearest < options.cancellation)) cancelled_everywhere = false;
    }
    if (std::abs(z) >= 1) pole.findings.push_back("unstable (|z| >= 1)");
    if (z.imag() == 0 || lambda.imag() == 0) pole.findings.push_back("real: not a vibration mode");
    else if (pole.zeta > options.max_zeta) pole.findings.push_back("overdamped (zeta above " + std::to_string(options.max_zeta).substr(0, 4) + ")");
    if (pole.f_hz > nyquist_band) pole.findings.push_back("above the band the sampling supports");
    if (cancelled_everywhere) pole.findings.push_back("cancelled by a zero in every channel");
    poles.push_back(pole);
    peak.push_back(h);
  }
  // Dominance relative to each channel's largest peak among the admissible poles.
  Eigen::VectorXd channel_max = Eigen::VectorXd::Zero(O);
  for (std::size_t i = 0; i < poles.size(); ++i)
    if (poles[i].findings.empty()) channel_max = channel_max.cwiseMax(peak[i]);
  std::vector<std::size_t> admissible;
  for (std::size_t i = 0; i < poles.size(); ++i) {
    double d = 0;
    for (int o = 0; o < O; ++o)
      if (channel_max[o] > 0) d = std::max(d, peak[i][o] / channel_max[o]);
    poles[i].dominance = d;
    if (poles[i].findings.empty()) admissible.push_back(i);
  }
  std::stable_sort(admissible.begin(), admissible.end(),
                   [&](std::size_t a, std::size_t b) { return poles[a].dominance > poles[b].dominance; });
  const std::size_t model_modes = static_cast<std::size_t>(q / 2);
  std::vector<std::size_t> chosen(admissible.begin(), admissible.begin() + std::min(admissible.size(), model_modes));
  for (std::size_t i = chosen.size(); i < admissible.size(); ++i)
    poles[admissible[i]].findings.push_back("phantom: weaker than the model's " + std::to_string(model_modes) + " modes");
  // Each candidate's response to the input (regressors 2 Re x and -2 Im x for Re r and Im r); a mode the record
  // does not show significantly in any channel (Wald chi-square of its residue below kMinChi2, 2 degrees of freedom,
  // from the unconstrained residue fit) is dropped and the rest refitted: the data show fewer modes than the model.
  constexpr double kMinChi2 = 50;
  std::vector<Eigen::VectorXcd> response(poles.size());
  for (std::size_t i : chosen) response[i] = pole_response(poles[i].lambda, u, dt, first_order_hold);
  auto regressors = [&](const std::vector<std::size_t>& set) {
    Eigen::MatrixXd Psi(N, 2 * static_cast<Eigen::Index>(set.size()));
    for (std::size_t k = 0; k < set.size(); ++k) {
      Psi.col(2 * static_cast<Eigen::Index>(k)) = 2 * response[set[k]].real();
      Psi.col(2 * static_cast<Eigen::Index>(k) + 1) = -2 * response[set[k]].imag();
    }
    return Psi;
  };
  for (;;) {
    if (chosen.empty())
      throw std::invalid_argument("the record shows no vibration mode significantly (" + out.model + " order " +
                                  std::to_string(n) + ", after pruning)");
    const Eigen::MatrixXd Psi = regressors(chosen);
    const Eigen::MatrixXd info = Psi.transpose() * Psi;
    const Eigen::MatrixXd info_inv = info.completeOrthogonalDecomposition().pseudoInverse();
    std::vector<double> chi2(chosen.size(), 0.0);
    for (int o = 0; o < O; ++o) {
      const Eigen::VectorXd& yo = y[static_cast<std::size_t>(o)];
      const Eigen::VectorXd rho = Psi.colPivHouseholderQr().solve(yo);
      const double s2 = (yo - Psi * rho).squaredNorm() / double(std::max<Eigen::Index>(N - rho.size(), 1));
      for (std::size_t k = 0; k < chosen.size(); ++k) {
        const Eigen::Index j = 2 * static_cast<Eigen::Index>(k);
        const Eigen::Matrix2d cov = s2 * info_inv.block<2, 2>(j, j);
        const Eigen::Vector2d r = rho.segment<2>(j);
        chi2[k] = std::max(chi2[k], r.dot(cov.completeOrthogonalDecomposition().solve(r)));
      }
    }
    std::vector<std::size_t> significant;
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      if (chi2[k] >= kMinChi2) significant.push_back(chosen[k]);
      else poles[chosen[k]].findings.push_back("not significant in the record (residue chi-square " +
                                               std::to_string(static_cast<long>(chi2[k])) + " < 50)");
    }
    if (significant.size() == chosen.size()) break;
    chosen = significant;
  }
  std::sort(chosen.begin(), chosen.end());
  std::vector<Complex> kept;
  for (std::size_t i : chosen) {
    poles[i].kept = true;
    kept.push_back(poles[i].lambda);
  }
  const NumeratorFit fit = fit_numerators(kept, u, y, sy, dt, first_order_hold, q, numerator_degree);
  IdentifiedTf& tf = out.tf;
  tf.input = input;
  tf.outputs = outputs;
  tf.denominator = fit.denominator;
  tf.numerators = fit.numerators;
  const double rss_w = fit.rss_w, yy_w = fit.yy_w;
  if (pole_covariance) {
    // The coefficients' covariance: the poles' through the whole fit (the denominator and the refitted residues, by
    // central differences), plus each numerator's given the poles. The two add: the residues refitted at fixed poles
    // are the joint estimate's conditional part, whose error is uncorrelated with the poles' to first order.
    const Eigen::Index m = static_cast<Eigen::Index>(kept.size());
    const Eigen::MatrixXd cov_poles = pole_covariance(kept);
    const Eigen::VectorXd base = stacked_coefficients(fit);
    Eigen::MatrixXd J(base.size(), 2 * m);
    for (Eigen::Index k = 0; k < 2 * m; ++k) {
      const double h = 1e-6 * std::abs(kept[static_cast<std::size_t>(k / 2)]);
      const Complex step = k % 2 ? Complex(0, h) : Complex(h, 0);
      std::vector<Complex> plus = kept, minus = kept;
      plus[static_cast<std::size_t>(k / 2)] += step;
      minus[static_cast<std::size_t>(k / 2)] -= step;
      J.col(k) = (stacked_coefficients(fit_numerators(plus, u, y, sy, dt, first_order_hold, q, numerator_degree)) -
                  stacked_coefficients(fit_numerators(minus, u, y, sy, dt, first_order_hold, q, numerator_degree))) /
                 (2 * h);
    }
    tf.covariance = J * cov_poles * J.transpose();
    Eigen::Index k = fit.denominator.size() - 1;
    for (const Eigen::MatrixXd& c : fit.covariance) {
      tf.covariance.block(k, k, c.rows(), c.cols()) += c;
      k += c.rows();
    }
  }
  out.residue_nrmse = yy_w > 0 ? std::sqrt(rss_w / yy_w) : 0;
  out.poles = poles;
  std::sort(out.poles.begin(), out.poles.end(), [](const ArxPole& a, const ArxPole& b) { return a.f_hz < b.f_hz; });
}

}  // namespace mbgen::methods
