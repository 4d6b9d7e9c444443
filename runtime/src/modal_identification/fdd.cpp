// Frequency-domain decomposition (Brincker, Zhang, Andersen 2001) and its enhanced damping estimate (EFDD): near
// a mode the output spectral matrix is nearly of rank one, its first singular value the mode's single-degree-of-
// freedom spectrum and its first singular vector the shape. That holds when the modes respond independently
// (forces at many points); one force drives them coherently and the first singular vector is the operating
// deflection shape, the neighbours included. So, on records, a mode's shape comes from its pole term in the half
// spectra and its damping from its bell in a modal filter of the spectral matrix (below).
#include "fft_transforms.hpp"
#include "mbgen/modal_identification/output_only_modal.hpp"
#include "numerics/constants.hpp"
#include "shape_metrics.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace mbgen {

namespace {

using numerics::kTwoPi;
constexpr double kLagsPerWindow = 8;  // lags up to 8 window lengths: exp(-8) of the correlation left out
constexpr double kRecordsPerWindow = 20;
constexpr double kPeakWindow = 0.01;  // a peak is the highest line within 1 % of its frequency
constexpr double kEnvelopeHigh = 0.8, kEnvelopeLow = 0.2;  // EFDD: extrema of the bell's correlation used
constexpr int kMinExtrema = 4;
constexpr Eigen::Index kMinBellFitLines = 5;  // 4 parameters
constexpr double kResidueWidths = 3;            // the residue's lines: within 3 windowed decays of the peak
constexpr Eigen::Index kMinResidueLines = 5;    // 3 coefficients
constexpr double kMinFilterConditioning = 0.1;  // the modal filter: least / largest singular value of the shapes

struct Spectra {
  Eigen::VectorXd f_hz;
  Eigen::MatrixXd singular;               // lines x channels
  std::vector<Eigen::VectorXcd> vectors;  // first singular vector per line
  // Records only (empty for FRFs): the half spectra F_ab = sum_(k>=0) w_k R_k(a, b) exp(-i 2 pi f k dt) of the
  // channel pairs (a, b) at a * channels + b, R_0, and the sample interval; G = dt (F + F^H - R_0).
  std::vector<Eigen::VectorXcd> half;
  Eigen::MatrixXd r0;
  double dt = 0;

  Eigen::MatrixXcd matrix(Eigen::Index j) const {  // G at line j
    const Eigen::Index l = r0.rows();
    Eigen::MatrixXcd G(l, l);
    for (Eigen::Index a = 0; a < l; ++a)
      for (Eigen::Index b = 0; b < l; ++b)
        G(a, b) = dt * (half[static_cast<std::size_t>(a * l + b)][j] +
                        std::conj(half[static_cast<std::size_t>(b * l + a)][j]) - r0(a, b));
    return G;
  }
};

// G(f) = dt sum_k w_k R_k exp(-i 2 pi f k dt) over k = -(K-1)..K-1 with R_-k = R_k^T and w_k = exp(-|k| dt / Tw),
// on the lines j / (2 K dt), j = 0..K; each (a, b) by one real FFT of the lags k >= 0: G_ab = dt (F_ab +
// conj(F_ba) - R_0(a, b)).
Spectra spectral_matrix(const ResponseData& data, Eigen::Index K, double window_s) {
  ResponseData all = data;
  all.references.clear();
  for (std::size_t c = 0; c < data.channels.size(); ++c) all.references.push_back(static_cast<int>(c));
  const std::vector<Eigen::MatrixXd> R = output_correlations(all, K);
  const Eigen::Index l = static_cast<Eigen::Index>(data.channels.size());
  modal_detail::RealTransforms fft(2 * K);
  std::vector<std::vector<Eigen::VectorXcd>> F(static_cast<std::size_t>(l));
  Eigen::VectorXd lagged(K);
  for (Eigen::Index a = 0; a < l; ++a)
    for (Eigen::Index b = 0; b < l; ++b) {
      for (Eigen::Index k = 0; k < K; ++k)
        lagged[k] = R[static_cast<std::size_t>(k)](a, b) * std::exp(-static_cast<double>(k) * data.dt / window_s);
      F[static_cast<std::size_t>(a)].push_back(fft.forward(lagged));
    }
  Spectra s;
  s.dt = data.dt;
  s.r0 = R[0];
  s.f_hz = Eigen::VectorXd::LinSpaced(K + 1, 0.0, 0.5 / data.dt);
  s.singular.resize(K + 1, l);
  Eigen::MatrixXcd G(l, l);
  for (Eigen::Index j = 0; j <= K; ++j) {
    for (Eigen::Index a = 0; a < l; ++a)
      for (Eigen::Index b = 0; b < l; ++b)
        G(a, b) = data.dt * (F[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)][j] +
                             std::conj(F[static_cast<std::size_t>(b)][static_cast<std::size_t>(a)][j]) - R[0](a, b));
    // Hermitian and positive semi-definite (the lag window's transform is positive): singular values are its
    // eigenvalues, descending.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eig(G);
    for (Eigen::Index c = 0; c < l; ++c) s.singular(j, c) = std::max(0.0, eig.eigenvalues()[l - 1 - c]);
    s.vectors.push_back(eig.eigenvectors().col(l - 1));
  }
  for (std::vector<Eigen::VectorXcd>& row : F)
    for (Eigen::VectorXcd& h : row) s.half.push_back(std::move(h));
  return s;
}

// A number for a note: 6 significant digits.
std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

double db(double x) { return 10 * std::log10(std::max(x, std::numeric_limits<double>::min())); }

// Peaks of the first singular value in [lo, hi): the highest line within 1 % of its frequency that stands at
// least `prominence_db` above the higher of the valleys between it and the next higher line on either side.
std::vector<Eigen::Index> find_peaks(const Spectra& s, Eigen::Index lo, Eigen::Index hi, double prominence_db) {
  const Eigen::VectorXd& s1 = s.singular.col(0);
  const double df = s.f_hz[1] - s.f_hz[0];
  std::vector<Eigen::Index> peaks;
  for (Eigen::Index j = lo; j < hi; ++j) {
    const Eigen::Index h =
        std::max<Eigen::Index>(2, static_cast<Eigen::Index>(std::ceil(kPeakWindow * s.f_hz[j] / df)));
    bool highest = true;
    for (Eigen::Index m = std::max(lo, j - h); m <= std::min(hi - 1, j + h) && highest; ++m)
      highest = m == j || s1[m] < s1[j] || (s1[m] == s1[j] && m > j);
    if (!highest) continue;
    double left = s1[j], right = s1[j];
    for (Eigen::Index m = j - 1; m >= lo && s1[m] <= s1[j]; --m) left = std::min(left, s1[m]);
    for (Eigen::Index m = j + 1; m < hi && s1[m] <= s1[j]; ++m) right = std::min(right, s1[m]);
    if (db(s1[j]) - db(std::max(left, right)) >= prominence_db) peaks.push_back(j);
  }
  return peaks;
}

// Parabola through three samples: the offset of its vertex from the middle one and its value there.
std::pair<double, double> vertex(double a, double b, double c) {
  const double denominator = a - 2 * b + c;
  if (denominator == 0) return {0.0, b};
  const double x = 0.5 * (a - c) / denominator;
  return {x, b - 0.25 * (a - c) * x};
}

// EFDD's damping: the bell's first singular values fitted, in the log domain, by the spectrum of one mode under
// white noise over a constant background (the other modes' tails and the noise under the bell),
// A / ((wn^2 - w^2)^2 + 4 sigma^2 w^2) + B, by Levenberg-Marquardt on (log A, wn, sigma, log B) from the
// logarithmic decrement's wn and sigma. The lag window's exp(-|tau| / Tw) makes that spectrum the one of decay
// sigma + 1 / Tw (to first order in sigma / wd), so sigma is the windowed decay. A fit of the bell's shape is not
// biased by the bell's edges as the decay of its inverse transform is: a bell cut where the mode's spectrum is
// still 20 dB up transforms into a correlation function that decays faster than the mode (on drawn truths the
// logarithmic decrement's damping was up to 50 % high, the fit's within 26 % and mostly within 10 %).
// The spectrum fitted is `bell` (lines a..b); the first singular values when it is empty.
// Returns {wn, sigma}; NaNs when the bell has too few lines or the fit does not converge.
std::pair<double, double> fit_bell(const Spectra& s, Eigen::Index a, Eigen::Index b, double wn0, double sigma0,
                                   const Eigen::VectorXd& bell = Eigen::VectorXd()) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Index n = b - a + 1;
  if (n < kMinBellFitLines) return {nan, nan};
  Eigen::VectorXd w(n), y(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    w[j] = kTwoPi * s.f_hz[a + j];
    const double value = bell.size() > 0 ? bell[j] : s.singular(a + j, 0);
    y[j] = std::log(std::max(value, std::numeric_limits<double>::min()));
  }
  const auto residuals = [&](const Eigen::Vector4d& p, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    r.resize(n);
    if (J) J->resize(n, 4);
    for (Eigen::Index j = 0; j < n; ++j) {
      const double d = p[1] * p[1] - w[j] * w[j];
      const double D = d * d + 4 * p[2] * p[2] * w[j] * w[j];
      const double peak = std::exp(p[0]) / D, back = std::exp(p[3]);
      const double m = peak + back;
      r[j] = y[j] - std::log(m);
      if (J) {
        (*J)(j, 0) = -peak / m;
        (*J)(j, 1) = peak / m * 4 * d * p[1] / D;
        (*J)(j, 2) = peak / m * 8 * p[2] * w[j] * w[j] / D;
        (*J)(j, 3) = -back / m;
      }
    }
  };
  Eigen::Vector4d p(0, wn0, sigma0, 0);
  p[0] = y.maxCoeff() + std::log(4 * sigma0 * sigma0 * wn0 * wn0);  // the peak at wn0
  p[3] = y.minCoeff() - std::log(100.0);                             // a background 20 dB below the bell's edge
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  residuals(p, r, &J);
  double cost = r.squaredNorm(), mu = 1e-3;
  bool converged = false;
  for (int it = 0; it < 300 && !converged; ++it) {
    const Eigen::Matrix4d JtJ = J.transpose() * J;
    const Eigen::Vector4d g = J.transpose() * r;
    Eigen::Matrix4d M = JtJ;
    for (int k = 0; k < 4; ++k) M(k, k) *= 1 + mu;
    const Eigen::Vector4d step = M.ldlt().solve(-g);
    const Eigen::Vector4d q = p + step;
    Eigen::VectorXd rq;
    residuals(q, rq, nullptr);
    if (q[2] > 0 && rq.allFinite() && rq.squaredNorm() < cost) {
      converged = cost - rq.squaredNorm() < 1e-14 * (1 + cost);
      p = q;
      residuals(p, r, &J);
      cost = r.squaredNorm();
      mu = std::max(mu / 10, 1e-12);
    } else {
      mu *= 10;
      converged = mu > 1e12;  // no step lowers the cost: a minimum
    }
  }
  if (!converged || !p.allFinite()) return {nan, nan};
  return {p[1], p[2]};
}

// The damping ratio of a bell fit's (wn, sigma), sigma the windowed decay: its damped frequency with the window's
// decay taken off.
double bell_zeta(double wn, double sigma, double window_decay) {
  const double decay = sigma - window_decay;
  return decay / std::sqrt(wn * wn - sigma * sigma + decay * decay);
}

// A mode's shape from the half spectra. R_k = sum_m phi_m mu_m^(k-1) g_m^T for k >= 1 (as SSI-cov's), and the lag
// window exp(-k dt / Tw) turns mu_m into mu_m exp(-dt / Tw), so
// F(z) = sum_(k>=0) w_k R_k z^-k = R_0 + sum_m phi_m g_m^T / (z - mu_m'), z = exp(i w dt), up to the lags cut at K
// (exp(-8)): one pole term per mode, as in an FRF, whatever the forces. Near the mode the other modes' terms and
// R_0 vary slowly: a constant and a slope. With the pole from EFDD (wd and the windowed decay sigma'), the residue
// phi g^T, the constant and the slope are linear least squares over the bell's lines within kResidueWidths decays
// of wd; the shape is the residue's left singular vector, phi (g holds every channel as a reference). Why not the
// first singular vector of G: with one force, or forces that drive the modes coherently, G = h h^H has rank one
// and that vector is the operating deflection shape h, the neighbouring modes' responses included (the spindle's
// second mode, at a fifth of its neighbour's response: MAC 0.925 to 0.953 with its shape, 0.989 and more so).
// Empty when too few lines.
Eigen::VectorXcd residue_shape(const Spectra& s, Eigen::Index a, Eigen::Index b, double wd, double sigma) {
  std::vector<Eigen::Index> lines;
  for (Eigen::Index j = a; j <= b; ++j)
    if (std::abs(kTwoPi * s.f_hz[j] - wd) <= kResidueWidths * sigma) lines.push_back(j);
  const Eigen::Index n = static_cast<Eigen::Index>(lines.size()), pairs = static_cast<Eigen::Index>(s.half.size());
  if (n < kMinResidueLines || pairs == 0) return {};
  const std::complex<double> mu = std::exp(std::complex<double>(-sigma, wd) * s.dt);
  Eigen::MatrixXcd B(n, 3), Y(n, pairs);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index j = lines[static_cast<std::size_t>(i)];
    const double w = kTwoPi * s.f_hz[j];
    B(i, 0) = 1.0 / (std::exp(std::complex<double>(0, w * s.dt)) - mu);
    B(i, 1) = 1;
    B(i, 2) = (w - wd) / sigma;
    for (Eigen::Index c = 0; c < pairs; ++c) Y(i, c) = s.half[static_cast<std::size_t>(c)][j];
  }
  const Eigen::MatrixXcd X = B.colPivHouseholderQr().solve(Y);
  const Eigen::Index l = s.r0.rows();
  Eigen::MatrixXcd residue(l, l);
  for (Eigen::Index c = 0; c < pairs; ++c) residue(c / l, c % l) = X(0, c);
  const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(residue, Eigen::ComputeThinU);
  if (!(svd.singularValues()[0] > 0)) return {};
  return svd.matrixU().col(0);
}

// Where a peak's bell lies and the start of its fit, for the modal filter.
struct Bell {
  Eigen::Index a = 0, b = -1;    // lines
  double wn = 0, sigma = 0;      // the fit's start; 0: EFDD stopped before it
};

// EFDD: the bell (lines around the peak whose first singular vector has MAC >= bell_mac with the peak's) taken
// back to the lag domain is the mode's correlation function r(tau) ~ exp(-sigma' tau) cos(w_d tau), sigma' its
// decay plus the lag window's 1 / Tw. The frequency from its zero crossings (w_d) and the logarithmic decrement of
// its extrema between 0.8 and 0.2 of r(0), both by least squares; the damping from fit_bell, started there (the
// decrement's when the fit fails). On records the shape from the pole's residue (residue_shape).
void enhance(const Spectra& s, Eigen::Index peak, double dt, double window_s, double bell_mac, double bell_db,
             FddPeak& out, Bell& bell) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.efdd_f_hz = out.zeta = nan;
  const Eigen::Index lines = s.f_hz.size(), K = lines - 1;
  const Eigen::VectorXcd& u = s.vectors[static_cast<std::size_t>(peak)];
  Eigen::Index a = peak, b = peak;
  const double floor = s.singular(peak, 0) * std::pow(10.0, -bell_db / 10);
  const auto in_bell = [&](Eigen::Index j) {
    return s.singular(j, 0) >= floor && modal_detail::shape_mac(s.vectors[static_cast<std::size_t>(j)], u) >= bell_mac;
  };
  while (a > 1 && in_bell(a - 1)) --a;
  while (b < K - 1 && in_bell(b + 1)) ++b;
  out.bell_lines = static_cast<int>(b - a + 1);
  bell.a = a;
  bell.b = b;
  Eigen::VectorXcd half = Eigen::VectorXcd::Zero(lines);
  for (Eigen::Index j = a; j <= b; ++j) half[j] = s.singular(j, 0);
  modal_detail::RealTransforms fft(2 * K);
  const Eigen::VectorXd r = fft.backward(half, K);
  if (!(r[0] > 0)) {
    out.note = "the bell's correlation function is not positive at lag 0";
    return;
  }
  std::vector<double> ext_t, ext_log, zero_t;
  // Up to the first extremum below 0.2 of r(0): the envelope, not |r| itself, which passes 0 every half period.
  for (Eigen::Index m = 1; m + 1 < K; ++m) {
    if ((r[m] > 0) != (r[m + 1] > 0)) zero_t.push_back((static_cast<double>(m) + r[m] / (r[m] - r[m + 1])) * dt);
    if (std::abs(r[m]) >= std::abs(r[m - 1]) && std::abs(r[m]) > std::abs(r[m + 1])) {
      const auto [x, value] = vertex(std::abs(r[m - 1]), std::abs(r[m]), std::abs(r[m + 1]));
      if (value < kEnvelopeLow * r[0]) break;
      if (value <= kEnvelopeHigh * r[0]) {
        ext_t.push_back((static_cast<double>(m) + x) * dt);
        ext_log.push_back(std::log(value));
      }
    }
  }
  if (ext_t.size() < kMinExtrema || zero_t.size() < kMinExtrema) {
    out.note = "too few cycles of the bell's correlation function between 0.8 and 0.2 of its start (" +
               std::to_string(ext_t.size()) + " extrema)";
    return;
  }
  const auto slope = [](const std::vector<double>& x, const std::vector<double>& y) {
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      sx += x[k];
      sy += y[k];
      sxx += x[k] * x[k];
      sxy += x[k] * y[k];
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
  };
  std::vector<double> index(zero_t.size());
  for (std::size_t k = 0; k < index.size(); ++k) index[k] = static_cast<double>(k);
  const double wd = std::acos(-1.0) / slope(index, zero_t);  // crossings every half period
  const double window_decay = window_s > 0 ? 1 / window_s : 0.0;  // 0: no lag window
  const double sigma = -slope(ext_t, ext_log) - window_decay;
  const double wn = std::sqrt(wd * wd + sigma * sigma);
  out.efdd_f_hz = wn / kTwoPi;
  bell.wn = wn;
  bell.sigma = std::max(sigma + window_decay, kTwoPi * (s.f_hz[1] - s.f_hz[0]));
  const auto [fit_wn, fit_sigma] = fit_bell(s, a, b, bell.wn, bell.sigma);
  double pole_wd = wd, pole_sigma = sigma + window_decay;  // the windowed pole
  if (std::isfinite(fit_wn) && std::isfinite(fit_sigma)) {
    out.zeta = bell_zeta(fit_wn, fit_sigma, window_decay);
    pole_wd = std::sqrt(std::max(0.0, fit_wn * fit_wn - fit_sigma * fit_sigma));
    pole_sigma = fit_sigma;
  } else {
    out.zeta = sigma / wn;
    out.note = "the fit of the bell failed (" + std::to_string(out.bell_lines) +
               " lines): damping from the logarithmic decrement";
  }
  if (pole_sigma > 0) {
    Eigen::VectorXcd shape = residue_shape(s, a, b, pole_wd, pole_sigma);
    if (shape.size() > 0) out.shape = std::move(shape);
  }
}

// EFDD's damping with the neighbours filtered out. The first singular value is |h|^2 when one force drives the
// modes, h = sum_m phi_m q_m: beside the mode's own bell it holds the neighbours' tails and their cross-terms with
// the mode, which skew the bell (the spindle's second mode: +10 % to +32 %, +19 % on average over six draws). The
// modal filter psi_m, the reciprocal basis of the peaks' shapes (psi_m^H phi_n = 1 for n = m, else 0), takes out
// the modal coordinate: psi_m^H G psi_m is the mode's own spectrum, fitted as the first singular value was. Only
// with at least two peaks and no more than the channels, and shapes far enough from parallel (a filter of nearly
// parallel shapes amplifies the noise); a mode whose filtered fit fails keeps its damping.
void filter_damping(const Spectra& s, const std::vector<Bell>& bells, double window_decay,
                    std::vector<FddPeak>& peaks) {
  const Eigen::Index count = static_cast<Eigen::Index>(peaks.size()), l = s.r0.rows();
  if (s.half.empty() || count < 2 || count > l) return;
  Eigen::MatrixXcd shapes(l, count);
  for (Eigen::Index m = 0; m < count; ++m) shapes.col(m) = peaks[static_cast<std::size_t>(m)].shape.normalized();
  const Eigen::VectorXd singular = Eigen::JacobiSVD<Eigen::MatrixXcd>(shapes).singularValues();
  if (!(singular[count - 1] >= kMinFilterConditioning * singular[0])) return;
  const Eigen::MatrixXcd filters = shapes * (shapes.adjoint() * shapes).inverse();
  for (Eigen::Index m = 0; m < count; ++m) {
    const Bell& bell = bells[static_cast<std::size_t>(m)];
    if (!(bell.wn > 0)) continue;
    const Eigen::VectorXcd psi = filters.col(m);
    Eigen::VectorXd spectrum(bell.b - bell.a + 1);
    for (Eigen::Index j = bell.a; j <= bell.b; ++j) spectrum[j - bell.a] = psi.dot(s.matrix(j) * psi).real();
    const auto [wn, sigma] = fit_bell(s, bell.a, bell.b, bell.wn, bell.sigma, spectrum);
    if (std::isfinite(wn) && std::isfinite(sigma)) {
      FddPeak& peak = peaks[static_cast<std::size_t>(m)];
      peak.zeta = bell_zeta(wn, sigma, window_decay);
      if (peak.note.rfind("the fit of the bell failed", 0) == 0) peak.note.clear();
    }
  }
}

// A damping ratio is what the lines resolve only when the mode's half-power band f (1 -+ zeta) holds a line; else
// (coarse lines, a lightly damped mode, or zeta <= 0: the bell no wider than the lag window makes it) it is not
// determined: NaN, and the note says why.
void check_resolved(const Spectra& s, FddPeak& peak) {
  if (!std::isfinite(peak.zeta)) return;
  const double f = std::isfinite(peak.efdd_f_hz) ? peak.efdd_f_hz : peak.f_hz, df = s.f_hz[1] - s.f_hz[0];
  const double lo = f * (1 - peak.zeta), hi = f * (1 + peak.zeta);
  if (peak.zeta > 0 && std::floor(hi / df) >= std::ceil(lo / df)) return;
  peak.note = "damping not determined: " +
              (peak.zeta > 0 ? "its half-power band, 2 zeta f = " + number_text(hi - lo) + " Hz wide, holds no line"
                             : "the bell decays no faster than the lag window") +
              " (lines every " + number_text(df) + " Hz)";
  peak.zeta = std::numeric_limits<double>::quiet_NaN();
}

// Peaks of the first singular value in lines lo..hi-1, each with its shape and EFDD's estimate.
void pick_peaks(const Spectra& s, Eigen::Index lo, Eigen::Index hi, double dt, const FddOptions& options,
                FddResult& out) {
  std::vector<Bell> bells;
  for (const Eigen::Index j : find_peaks(s, std::max<Eigen::Index>(lo, 1), hi, options.prominence_db)) {
    FddPeak p;
    p.f_hz = s.f_hz[j];
    p.shape = s.vectors[static_cast<std::size_t>(j)];
    p.sv_db = db(s.singular(j, 0));
    bells.emplace_back();
    enhance(s, j, dt, out.window_s, options.bell_mac, options.bell_db, p, bells.back());
    out.peaks.push_back(std::move(p));
  }
  filter_damping(s, bells, out.window_s > 0 ? 1 / out.window_s : 0.0, out.peaks);
  for (FddPeak& p : out.peaks) check_resolved(s, p);
}

// The FRFs' lines as multiples of their spacing: index j of line f_j = j df, or an error.
std::vector<Eigen::Index> frf_line_indices(const ModalData& frfs, double& df) {
  const Eigen::VectorXd& f = frfs.f_hz;
  if (f.size() < 2) throw std::invalid_argument("FDD of FRFs needs at least 2 lines");
  df = f[1] - f[0];
  std::vector<Eigen::Index> index;
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    const double j = std::round(f[k] / df);
    if (std::abs(f[k] / df - j) > 1e-6)
      throw std::invalid_argument("FDD of FRFs needs lines equally spaced on the multiples of their spacing (" +
                                  std::to_string(df) + " Hz); line " + std::to_string(k + 1) + " is at " +
                                  std::to_string(f[k]) + " Hz");
    index.push_back(static_cast<Eigen::Index>(j));
  }
  return index;
}

}  // namespace

double frf_equivalent_dt(const ModalData& frfs) {
  double df = 0;
  const std::vector<Eigen::Index> index = frf_line_indices(frfs, df);
  return 1 / (2 * static_cast<double>(index.back()) * df);
}

FddResult fdd(const ResponseData& data, const FddOptions& options) {
  Eigen::Index shortest = std::numeric_limits<Eigen::Index>::max();
  for (const Eigen::MatrixXd& y : data.records) shortest = std::min(shortest, y.rows());
  FddResult out;
  out.window_s = options.window_s > 0 ? options.window_s
                                      : static_cast<double>(shortest) * data.dt / kRecordsPerWindow;
  const Eigen::Index K = std::min<Eigen::Index>(
      shortest / 2, static_cast<Eigen::Index>(std::ceil(kLagsPerWindow * out.window_s / data.dt)));
  if (K < 16) throw std::invalid_argument("the lag window of " + std::to_string(out.window_s) + " s holds fewer "
                                          "than 16 samples");
  const Spectra s = spectral_matrix(data, K, out.window_s);
  out.f_hz = s.f_hz;
  out.singular = s.singular;
  const double df = s.f_hz[1];
  const Eigen::Index lo = options.lo_hz > 0 ? static_cast<Eigen::Index>(std::ceil(options.lo_hz / df)) : 2;
  const Eigen::Index hi = options.hi_hz > 0
                               ? std::min<Eigen::Index>(K, static_cast<Eigen::Index>(options.hi_hz / df) + 1)
                               : static_cast<Eigen::Index>(0.95 * static_cast<double>(K));
  pick_peaks(s, lo, hi, data.dt, options, out);
  return out;
}

// G(f) = H(f) H(f)^H (responses x responses, summed over the forces): the spectral matrix of the responses to unit
// white forces at the inputs, on the lines j df, j = 0..K (K df the highest FRF line; lines without data zero).
// Its inverse transform is the correlation of those responses at the interval 1 / (2 K df); nothing windows it.
FddResult fdd_of_frfs(const ModalData& frfs, const FddOptions& options) {
  double df = 0;
  const std::vector<Eigen::Index> index = frf_line_indices(frfs, df);
  const Eigen::Index K = index.back();
  if (K < 16) throw std::invalid_argument("FDD of FRFs needs a highest line at 16 or more times the spacing");
  // A roving hammer (fewer outputs than inputs): by reciprocity, H^T holds the responses at the hammer points to
  // forces at the sensors, as the FRF path fits it transposed.
  const bool transposed = frfs.outputs.size() < frfs.inputs.size();
  const Eigen::Index l = static_cast<Eigen::Index>(transposed ? frfs.inputs.size() : frfs.outputs.size());
  const Eigen::Index m = static_cast<Eigen::Index>(transposed ? frfs.outputs.size() : frfs.inputs.size());
  Spectra s;
  s.f_hz = Eigen::VectorXd::LinSpaced(K + 1, 0.0, static_cast<double>(K) * df);
  s.singular = Eigen::MatrixXd::Zero(K + 1, l);
  s.vectors.assign(static_cast<std::size_t>(K + 1), Eigen::VectorXcd::Unit(l, 0));
  Eigen::MatrixXcd H(l, m);
  for (std::size_t k = 0; k < index.size(); ++k) {
    H.setZero();
    for (std::size_t c = 0; c < frfs.channels.size(); ++c) {
      const int o = frfs.channels[c].output, i = frfs.channels[c].input;
      H(transposed ? i : o, transposed ? o : i) = frfs.H(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c));
    }
    const Eigen::MatrixXcd G = H * H.adjoint();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eig(G);
    const Eigen::Index j = index[k];
    for (Eigen::Index c = 0; c < l; ++c) s.singular(j, c) = std::max(0.0, eig.eigenvalues()[l - 1 - c]);
    s.vectors[static_cast<std::size_t>(j)] = eig.eigenvectors().col(l - 1);
  }
  FddResult out;
  out.window_s = 0;
  out.f_hz = s.f_hz;
  out.singular = s.singular;
  out.frf_inputs = transposed ? frfs.outputs : frfs.inputs;
  out.frf_transposed = transposed;
  const Eigen::Index lo = options.lo_hz > 0 ? static_cast<Eigen::Index>(std::ceil(options.lo_hz / df)) : index.front();
  const Eigen::Index hi = options.hi_hz > 0
                               ? std::min<Eigen::Index>(K + 1, static_cast<Eigen::Index>(options.hi_hz / df) + 1)
                               : K + 1;
  pick_peaks(s, lo, hi, 1 / (2 * static_cast<double>(K) * df), options, out);
  return out;
}

}  // namespace mbgen
