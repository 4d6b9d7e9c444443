// Frequency-domain decomposition (Brincker, Zhang, Andersen 2001) and its enhanced damping estimate (EFDD): near
// a mode the output spectral matrix is nearly of rank one, its first singular value the mode's single-degree-of-
// freedom spectrum and its first singular vector the shape.
#include "fft_transforms.hpp"
#include "mbgen/output_only_modal.hpp"
#include "shape_metrics.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mbgen {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kLagsPerWindow = 8;  // lags up to 8 window lengths: exp(-8) of the correlation left out
constexpr double kRecordsPerWindow = 20;
constexpr double kPeakWindow = 0.01;  // a peak is the highest line within 1 % of its frequency
constexpr double kEnvelopeHigh = 0.8, kEnvelopeLow = 0.2;  // EFDD: extrema of the bell's correlation used
constexpr int kMinExtrema = 4;

struct Spectra {
  Eigen::VectorXd f_hz;
  Eigen::MatrixXd singular;               // lines x channels
  std::vector<Eigen::VectorXcd> vectors;  // first singular vector per line
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
  return s;
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

// EFDD: the bell (lines around the peak whose first singular vector has MAC >= bell_mac with the peak's) taken
// back to the lag domain is the mode's correlation function r(tau) ~ exp(-sigma' tau) cos(w_d tau), sigma' its
// decay plus the lag window's 1 / Tw. The decay from the logarithmic decrement of its extrema between 0.8 and 0.2
// of r(0), w_d from its zero crossings, both by least squares.
void enhance(const Spectra& s, Eigen::Index peak, double dt, double window_s, double bell_mac, double bell_db,
             FddPeak& out) {
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
  const double sigma = -slope(ext_t, ext_log) - 1 / window_s;
  const double wn = std::sqrt(wd * wd + sigma * sigma);
  out.efdd_f_hz = wn / kTwoPi;
  out.zeta = sigma / wn;
  if (!(out.zeta > 0)) out.note = "the bell decays no faster than the lag window: damping below what it resolves";
}

}  // namespace

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
  for (const Eigen::Index j : find_peaks(s, std::max<Eigen::Index>(lo, 1), hi, options.prominence_db)) {
    FddPeak p;
    p.f_hz = s.f_hz[j];
    p.shape = s.vectors[static_cast<std::size_t>(j)];
    p.sv_db = db(s.singular(j, 0));
    enhance(s, j, data.dt, out.window_s, options.bell_mac, options.bell_db, p);
    out.peaks.push_back(std::move(p));
  }
  return out;
}

}  // namespace mbgen
