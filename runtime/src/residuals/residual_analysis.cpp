#include "mbgen/residuals/residual_analysis.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <utility>

#include "text/string_format.hpp"
#include "numerics/window_median.hpp"
#include "numerics/constants.hpp"

namespace mbgen {

namespace {

using detail::format;

double db(double ratio) { return 20.0 * std::log10(std::max(ratio, 1e-300)); }

// Index of the largest |h| in [lo, hi].
int argmax_abs(const Eigen::VectorXcd& h, int lo, int hi) {
  int best = lo;
  for (int i = lo; i <= hi; ++i)
    if (std::abs(h[i]) > std::abs(h[best])) best = i;
  return best;
}

// The peak in `peaks` nearest to frequency f, or -1.
int nearest_peak(const std::vector<int>& peaks, const std::vector<double>& f, double target) {
  int best = -1;
  for (int p : peaks)
    if (best < 0 || std::abs(f[static_cast<std::size_t>(p)] - target) < std::abs(f[static_cast<std::size_t>(best)] - target))
      best = p;
  return best;
}

// The measured magnitude averaged over three lines, so that noise does not make peaks of its own.
Eigen::VectorXcd smoothed(const Eigen::VectorXcd& h) {
  Eigen::VectorXcd out = h;
  for (Eigen::Index i = 1; i + 1 < h.size(); ++i) out[i] = (std::abs(h[i - 1]) + std::abs(h[i]) + std::abs(h[i + 1])) / 3.0;
  return out;
}

struct Band {
  int lo, hi;
  double mean_z;
};

// Runs of lines whose running mean of z exceeds level(i), widened by the window and merged across short gaps.
template <class Level>
std::vector<Band> bands_above(const Eigen::VectorXd& z, const ResidualOptions& o, Level level, int from, int to) {
  const int n = static_cast<int>(z.size());
  const int half = std::max(0, o.window / 2);
  std::vector<double> running(static_cast<std::size_t>(n));
  for (int i = from; i <= to; ++i) {
    const int lo = std::max(from, i - half), hi = std::min(to, i + half);
    running[static_cast<std::size_t>(i)] = z.segment(lo, hi - lo + 1).mean();
  }
  std::vector<Band> bands;
  for (int i = from; i <= to;) {
    if (running[static_cast<std::size_t>(i)] <= level(i)) {
      ++i;
      continue;
    }
    int j = i;
    while (j + 1 <= to && running[static_cast<std::size_t>(j + 1)] > level(j + 1)) ++j;
    // Widen by the window so the band covers the lines that raised the running mean.
    const int lo = std::max(from, i - half), hi = std::min(to, j + half);
    if (!bands.empty() && lo - bands.back().hi <= o.window) {
      bands.back().hi = hi;  // a short gap between two bands is one finding, split by noise
      bands.back().mean_z = z.segment(bands.back().lo, hi - bands.back().lo + 1).mean();
    } else {
      bands.push_back({lo, hi, z.segment(lo, hi - lo + 1).mean()});
    }
    i = j + 1;
  }
  return bands;
}

std::vector<Band> significant_bands(const Eigen::VectorXd& z, const ResidualOptions& o) {
  return bands_above(z, o, [&](int) { return o.threshold; }, 0, static_cast<int>(z.size()) - 1);
}

// Within a wide band, the sub-bands that stand out of the residual's own floor (ResidualOptions::contrast).
std::vector<Band> contrasted_bands(const Eigen::VectorXd& z, const Band& band, const ResidualOptions& o) {
  const int half = std::max(1, o.floor_window / 2);
  std::vector<double> floor(static_cast<std::size_t>(z.size()), 0.0);
  std::vector<double> window;
  for (int i = band.lo; i <= band.hi; ++i) {
    const int lo = std::max(band.lo, i - half), hi = std::min(band.hi, i + half);
    floor[static_cast<std::size_t>(i)] = detail::window_median(z.data() + lo, z.data() + hi + 1, window);
  }
  return bands_above(
      z, o, [&](int i) { return std::max(o.threshold, o.contrast * floor[static_cast<std::size_t>(i)]); }, band.lo,
      band.hi);
}

// |H_meas| / |H_model| at line i in dB, each magnitude taken at least at the noise level there: no measurement
// tells a ratio beyond its own signal-to-noise ratio (a model that has almost no response at a line made
// "109.8 dB" findings, a figure no data can support).
double measurable_ratio_db(const ChannelResidual& c, int i) {
  const double noise = std::max(c.sigma[i], 1e-300);
  return db(std::max(std::abs(c.measured[i]), noise) / std::max(std::abs(c.model[i]), noise));
}

// How far the measured magnitude at a peak rises above its surroundings (the higher of the lowest levels either
// side before a higher peak, peak_prominence_db's reference), as a multiple of the noise there: a resonance the
// model lacks is what the model would have to add, and its size is that rise, not its ratio to a model that may
// be orders of magnitude off everywhere around it.
struct PeakRise {
  double db = 0;         // the rise in dB
  double z = 0;          // (rise / sigma)^2, on the scale of the normalized residual
};
PeakRise peak_rise(const Eigen::VectorXcd& smooth, const Eigen::VectorXd& sigma, int p) {
  const int n = static_cast<int>(smooth.size());
  const double m = std::abs(smooth[p]);
  double left = m, right = m;
  for (int j = p - 1; j >= 0 && std::abs(smooth[j]) <= m; --j) left = std::min(left, std::abs(smooth[j]));
  for (int j = p + 1; j < n && std::abs(smooth[j]) <= m; ++j) right = std::min(right, std::abs(smooth[j]));
  const double base = std::max(left, right), noise = std::max(sigma[p], 1e-300);
  PeakRise r;
  r.db = db(m / std::max(base, noise));
  r.z = (m - base) * (m - base) / (noise * noise);
  return r;
}

// `smooth`: smoothed(c.measured), computed once per channel.
void describe_unexplained_resonance(const ChannelResidual& c, const Eigen::VectorXcd& smooth, int peak,
                                    Discrepancy& d) {
  d.kind = "unexplained_resonance";
  d.f_hz = c.f_hz[static_cast<std::size_t>(peak)];
  d.size_db = peak_rise(smooth, c.sigma, peak).db;
  d.text = format("a resonance near %.1f Hz on %s (%s) that the model does not have: it rises %.1f dB above the "
                  "response around it",
                  d.f_hz, c.channel.c_str(), c.data_set.c_str(), d.size_db);
}

Discrepancy classify(const ChannelResidual& c, const Eigen::VectorXcd& smooth, const Band& band,
                     const std::vector<int>& data_peaks, const std::vector<int>& model_peaks,
                     const ResidualOptions& o) {
  const std::vector<double>& f = c.f_hz;
  const int n = static_cast<int>(f.size());
  Discrepancy d;
  d.channel = c.channel;
  d.data_set = c.data_set;
  d.f_lo = f[static_cast<std::size_t>(band.lo)];
  d.f_hi = f[static_cast<std::size_t>(band.hi)];
  d.significance = band.mean_z;

  // A data peak inside the band? The one nearest the worst line: a band can span many modes (a grossly wrong
  // model's runs over a whole channel), and its highest peak may be one the model matches.
  int worst = band.lo;
  double worst_z = -1;
  for (int i = band.lo; i <= band.hi; ++i) {
    const double zi = normalized_residual(c.measured[i], c.model[i], c.sigma[i]);
    if (zi > worst_z) worst_z = zi, worst = i;
  }
  int data_peak = -1;
  for (int p : data_peaks) {
    if (p < band.lo || p > band.hi) continue;
    const auto at_hz = [&](int i) { return f[static_cast<std::size_t>(i)]; };
    const double distance = std::abs(at_hz(p) - at_hz(worst));
    const double best = data_peak < 0 ? 0.0 : std::abs(at_hz(data_peak) - at_hz(worst));
    if (data_peak < 0 || distance < best ||
        (distance == best && std::abs(c.measured[p]) > std::abs(c.measured[data_peak])))
      data_peak = p;
  }
  const int at = data_peak >= 0 ? data_peak : argmax_abs(c.measured - c.model, band.lo, band.hi);
  d.f_hz = f[static_cast<std::size_t>(at)];
  d.size_db = measurable_ratio_db(c, at);

  const std::string where = format("%s (%s)", c.channel.c_str(), c.data_set.c_str());
  if (data_peak >= 0) {
    const int model_peak = nearest_peak(model_peaks, f, d.f_hz);
    const double rel = model_peak >= 0 ? std::abs(f[static_cast<std::size_t>(model_peak)] - d.f_hz) / d.f_hz : 1e300;
    // A model peak two or more lines from the data's is a frequency difference, however close: where a
    // resonance is narrower than a line (a lightly damped mode on coarse lines), such a shift changes the height
    // at the peak line by tens of dB, which is no damping mismatch.
    const bool other_line = model_peak >= 0 && std::abs(model_peak - data_peak) >= 2;
    if (rel <= o.peak_tolerance && other_line) {
      d.kind = "frequency_shift";
      d.model_f_hz = f[static_cast<std::size_t>(model_peak)];
      d.text = format("the resonance at %.1f Hz on %s sits at %.1f Hz in the model (%+.2f %%)", d.f_hz, where.c_str(),
                      d.model_f_hz, 100.0 * (d.model_f_hz - d.f_hz) / d.f_hz);
    } else if (rel <= o.peak_tolerance && std::abs(d.size_db) < 1.0) {
      // The peak has the model's height but the residual is large: the difference is in phase, which at a
      // resonance turns by 90 degrees over the half-power band. A frequency off by less than the line spacing
      // shows so (a damping mismatch changes the height).
      d.kind = "frequency_shift";
      d.model_f_hz = f[static_cast<std::size_t>(model_peak)];
      // The phase where the residual is largest (at the peak line itself it may differ by a fraction of a degree).
      const double phase_deg = std::abs(std::arg(c.measured[worst] / c.model[worst])) * 180.0 / numerics::kPi;
      d.text = format("the resonance near %.1f Hz on %s has the model's height (%+.1f dB) but is %.1f degrees out of "
                      "phase with it at %.1f Hz: its frequency differs by less than a line",
                      d.f_hz, where.c_str(), d.size_db, phase_deg, f[static_cast<std::size_t>(worst)]);
    } else if (rel <= o.peak_tolerance) {
      d.kind = "damping_mismatch";
      d.model_f_hz = f[static_cast<std::size_t>(model_peak)];
      d.text = format("the resonance near %.1f Hz on %s is %.1f dB %s than the model: its damping does not match",
                           d.f_hz, where.c_str(), std::abs(d.size_db), d.size_db > 0 ? "higher" : "lower");
    } else if (rel <= 0.25) {
      d.kind = "frequency_shift";
      d.model_f_hz = f[static_cast<std::size_t>(model_peak)];
      d.text = format("the resonance at %.1f Hz on %s sits at %.1f Hz in the model (%+.1f %%)", d.f_hz, where.c_str(),
                           d.model_f_hz, 100.0 * (d.model_f_hz - d.f_hz) / d.f_hz);
    } else {
      describe_unexplained_resonance(c, smooth, data_peak, d);
    }
    return d;
  }
  if (band.lo == 0) {
    d.kind = "static_compliance";
    d.text = format("below %.1f Hz the measured %s is %.1f dB %s than the model: static compliance differs",
                         d.f_hi, where.c_str(), std::abs(d.size_db), d.size_db > 0 ? "higher" : "lower");
  } else if (band.hi == n - 1) {
    d.kind = "mass_line";
    d.text = format("above %.1f Hz the measured %s is %.1f dB %s than the model: the mass line differs", d.f_lo,
                         where.c_str(), std::abs(d.size_db), d.size_db > 0 ? "higher" : "lower");
  } else if (d.size_db < -3.0) {
    d.kind = "unexplained_antiresonance";
    d.text = format("a dip near %.1f Hz on %s that the model does not have (%.1f dB)", d.f_hz, where.c_str(), d.size_db);
  } else if (const double phase = std::abs(std::arg(c.measured[at] / c.model[at]));
             phase > std::abs(d.size_db) * std::log(10.0) / 20.0) {
    // Where the residual is largest the miss is more in phase than in magnitude (compared as the parts of
    // ln(data / model): radians against nepers), so it is said in degrees; "by up to 0.0 dB" said nothing.
    d.kind = "misfit";
    const double phase_deg = phase * 180.0 / numerics::kPi;
    d.text = format("between %.1f and %.1f Hz the model misses %s in phase: by %.1f degrees at %.1f Hz (%.1f dB in "
                    "magnitude)",
                    d.f_lo, d.f_hi, where.c_str(), phase_deg, d.f_hz, std::abs(d.size_db));
  } else {
    d.kind = "misfit";
    d.text = format("between %.1f and %.1f Hz the model misses %s by up to %.1f dB", d.f_lo, d.f_hi, where.c_str(),
                         std::abs(d.size_db));
  }
  return d;
}

// Every clear resonance of the data in a band the model misses, when the model has no peak within 25 % of it: a
// band is classified once, by the peak nearest its worst line, and a band over a whole channel (a model far off)
// would otherwise name one of several resonances the model lacks. A peak counts when both the residual around it
// and its rise over its surroundings exceed the finding threshold on the normalized residual's scale (noise alone
// passes either at the family-wise false-alarm rate), so the noise's own bumps in a misfit band are not peaks.
std::vector<Discrepancy> resonances_missing_in_band(const ChannelResidual& c, const Eigen::VectorXcd& smooth,
                                                    const Eigen::VectorXd& z,
                                                    const Band& band, const std::vector<int>& data_peaks,
                                                    const std::vector<int>& model_peaks, const ResidualOptions& o) {
  std::vector<Discrepancy> found;
  const int n = static_cast<int>(z.size()), half = std::max(0, o.window / 2);
  for (int p : data_peaks) {
    if (p < band.lo || p > band.hi) continue;
    const double fp = c.f_hz[static_cast<std::size_t>(p)];
    const int model_peak = nearest_peak(model_peaks, c.f_hz, fp);
    if (model_peak >= 0 && std::abs(c.f_hz[static_cast<std::size_t>(model_peak)] - fp) <= 0.25 * fp) continue;
    const int lo = std::max(0, p - half), hi = std::min(n - 1, p + half);
    const double local_z = z.segment(lo, hi - lo + 1).mean();
    if (local_z <= o.threshold || peak_rise(smooth, c.sigma, p).z <= o.threshold) continue;
    Discrepancy d;
    d.channel = c.channel;
    d.data_set = c.data_set;
    d.f_lo = c.f_hz[static_cast<std::size_t>(lo)];
    d.f_hi = c.f_hz[static_cast<std::size_t>(hi)];
    d.significance = local_z;
    describe_unexplained_resonance(c, smooth, p, d);
    found.push_back(std::move(d));
  }
  return found;
}

// A phase difference growing linearly with frequency (a delay) across the whole channel.
bool phase_trend(const ChannelResidual& c, Discrepancy& d) {
  const int n = static_cast<int>(c.f_hz.size());
  if (n < 8) return false;
  // Weighted least squares of the phase of H_meas / H_model against f, weights |H_model|^2 / sigma^2.
  double sw = 0, sf = 0, sp = 0, sff = 0, sfp = 0;
  for (int i = 0; i < n; ++i) {
    const std::complex<double> ratio = c.measured[i] / c.model[i];
    const double w = std::norm(c.model[i]) / std::max(c.sigma[i] * c.sigma[i], 1e-300);
    const double ph = std::arg(ratio), fi = c.f_hz[static_cast<std::size_t>(i)];
    sw += w, sf += w * fi, sp += w * ph, sff += w * fi * fi, sfp += w * fi * ph;
  }
  const double den = sw * sff - sf * sf;
  if (den <= 0) return false;
  const double slope = (sw * sfp - sf * sp) / den;          // rad per Hz
  const double slope_std = std::sqrt(sw / den / 2.0);       // each phase has variance ~ sigma^2 / (2 |H|^2)
  const double delay = -slope / numerics::kTwoPi;
  const double phase_at_top = std::abs(slope * c.f_hz.back());
  if (std::abs(slope) < 8.0 * slope_std || phase_at_top < 0.01) return false;  // significant and over half a degree
  d.kind = "phase_trend";
  d.channel = c.channel;
  d.data_set = c.data_set;
  d.f_lo = c.f_hz.front();
  d.f_hi = c.f_hz.back();
  d.f_hz = c.f_hz.back();
  d.significance = std::abs(slope) / slope_std;
  d.delay_s = delay;
  d.text = format("the phase of %s (%s) drifts from the model's by %.1f degrees at %.0f Hz, as a delay of %.3g s would",
                       c.channel.c_str(), c.data_set.c_str(), phase_at_top * 180.0 / numerics::kPi, c.f_hz.back(), delay);
  return true;
}

// One mode shows on every channel: findings of one kind within a few per cent of each other are one finding,
// kept on the channel where it is strongest and noting the others. On one channel they are one finding too (a
// wide band and the sub-band that stands out inside it, classified alike: the beam's 687 Hz mode was listed twice).
std::vector<Discrepancy> merge_across_channels(std::vector<Discrepancy> all) {
  std::stable_sort(all.begin(), all.end(), [](const Discrepancy& a, const Discrepancy& b) { return a.significance > b.significance; });
  std::vector<Discrepancy> kept;
  std::vector<std::set<std::pair<std::string, std::string>>> others;  // the other channels each kept one was seen on
  for (const Discrepancy& d : all) {
    bool merged = false;
    for (std::size_t k = 0; k < kept.size() && !merged; ++k) {
      const Discrepancy& m = kept[k];
      if (m.kind == d.kind && std::abs(m.f_hz - d.f_hz) <= 0.02 * std::max(m.f_hz, d.f_hz)) {
        if (m.channel != d.channel || m.data_set != d.data_set) others[k].insert({d.channel, d.data_set});
        merged = true;
      }
    }
    if (!merged) {
      kept.push_back(d);
      others.emplace_back();
    }
  }
  for (std::size_t k = 0; k < kept.size(); ++k)
    if (const std::size_t n = others[k].size(); n > 0)
      kept[k].text += format(" (also seen on %d other channel%s)", static_cast<int>(n), n > 1 ? "s" : "");
  return kept;
}

}  // namespace

double peak_prominence_db(const Eigen::VectorXcd& h, int i) {
  const int n = static_cast<int>(h.size());
  const double none = -std::numeric_limits<double>::infinity();
  if (i <= 0 || i + 1 >= n) return none;
  const double m = std::abs(h[i]);
  if (!(m > std::abs(h[i - 1]) && m >= std::abs(h[i + 1]))) return none;
  double left = m, right = m;
  for (int j = i - 1; j >= 0 && std::abs(h[j]) <= m; --j) left = std::min(left, std::abs(h[j]));
  for (int j = i + 1; j < n && std::abs(h[j]) <= m; ++j) right = std::min(right, std::abs(h[j]));
  return db(m / std::max(left, right));
}

std::vector<int> magnitude_peaks(const Eigen::VectorXcd& h, double prominence_db) {
  std::vector<int> peaks;
  for (int i = 1; i + 1 < static_cast<int>(h.size()); ++i)
    if (peak_prominence_db(h, i) >= prominence_db) peaks.push_back(i);
  return peaks;
}

namespace {

// P(Gamma(w, 1) > w t): the chance that the mean of w independent Exp(1) variables (z of noise alone) exceeds t.
double independent_tail(int w, double t) {
  const double x = w * t;
  double term = 1, sum = 1;
  for (int k = 1; k < w; ++k) sum += (term *= x / k);
  return std::exp(-x) * sum;
}

// The lowest level at or above options.threshold at which `expected(level)`, the number of windows noise alone is
// expected to raise above it (falling with the level), is at most options.false_alarm_rate.
template <class Expected>
double lowest_level(const ResidualOptions& options, Expected expected) {
  double lo = options.threshold;
  if (expected(lo) <= options.false_alarm_rate) return lo;
  double hi = std::max(lo, 1.0);  // doubling from a level of 0 would never move
  while (expected(hi) > options.false_alarm_rate) hi *= 2;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (expected(mid) > options.false_alarm_rate ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace

double finding_threshold(const ResidualOptions& options, long lines) {
  const int w = std::max(1, options.window);
  const double n = static_cast<double>(std::max(lines, 1L));
  return lowest_level(options, [&](double t) { return n * independent_tail(w, t); });
}

namespace {

// Noise whose lines correlate as `rho` (lag 1, 2, ...): z_k = |e_k|^2 with e complex Gaussian of correlation matrix R
// (R_ij = rho_|i-j|), so a window's sum of z is sum_i lambda_i E_i, lambda the eigenvalues of R and E_i independent
// Exp(1). The eigenvalues for w neighbouring lines; null when they are not distinct enough for eigen_tail's sum.
std::optional<Eigen::VectorXd> window_eigenvalues(int w, const std::vector<double>& rho) {
  Eigen::MatrixXd R = Eigen::MatrixXd::Identity(w, w);
  for (int i = 0; i < w; ++i)
    for (int j = 0; j < w; ++j) {
      const std::size_t lag = static_cast<std::size_t>(std::abs(i - j));
      if (lag > 0 && lag <= rho.size()) R(i, j) = rho[lag - 1];
    }
  const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(R, Eigen::EigenvaluesOnly).eigenvalues();
  for (int i = 0; i < w; ++i)
    for (int j = i + 1; j < w; ++j)
      if (std::abs(lambda[i] - lambda[j]) < 1e-6 * lambda.maxCoeff()) return std::nullopt;
  return lambda;
}

// P(sum_i lambda_i E_i > w t), E_i independent Exp(1), for distinct eigenvalues lambda: sum_i prod_{j != i}
// lambda_i / (lambda_i - lambda_j) exp(-w t / lambda_i).
double eigen_tail(const Eigen::VectorXd& lambda, int w, double t) {
  double p = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    if (!(lambda[i] > 0)) continue;  // a direction without noise adds nothing
    double weight = 1;
    for (Eigen::Index j = 0; j < lambda.size(); ++j)
      if (j != i && lambda[j] > 0) weight *= lambda[i] / (lambda[i] - lambda[j]);
    p += weight * std::exp(-w * t / lambda[i]);
  }
  return std::clamp(p, 0.0, 1.0);
}

// The tail with sigma^2 estimated: z = |e|^2 / (sigma^2 S), S = chi^2_dof / dof independent of e, so the window's
// mean exceeds t when the exact one exceeds t S: the tail averaged over S's density (Simpson's rule over S's mean
// +- 10 standard deviations). dof <= 0: sigma exact. `exact_tail(t)` is the tail with sigma exact: eigen_tail for
// correlated lines, independent_tail for independent ones.
template <class ExactTail>
double window_tail(ExactTail exact_tail, double t, double dof) {
  if (!(dof > 0)) return exact_tail(t);
  const double sd = std::sqrt(2.0 / dof), hi = 1.0 + 10.0 * sd, lo = std::max(1e-9, 1.0 - 10.0 * sd);
  const int n = 400;  // even
  const double h = (hi - lo) / n, k = dof / 2;
  const auto density = [&](double s) {  // of chi^2_dof / dof at s
    return std::exp(std::log(dof) + (k - 1) * std::log(dof * s) - dof * s / 2 - k * std::log(2.0) - std::lgamma(k));
  };
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double s = lo + i * h, weight = i == 0 || i == n ? 1 : i % 2 ? 4 : 2;
    sum += weight * density(s) * exact_tail(t * s);
  }
  return std::clamp(sum * h / 3, 0.0, 1.0);
}

}  // namespace

double finding_threshold(const ResidualOptions& options, const std::vector<ChannelResidual>& channels) {
  const int w = std::max(1, options.window);
  long independent_lines = 0;
  // Channels whose windows have a tail of their own: correlated lines (lambda), or a noise level estimated with
  // `dof` degrees of freedom (a record's, or a measured FRF's whose coherence scatters), or both.
  struct OwnTail {
    double lines;
    std::optional<Eigen::VectorXd> lambda;
    double dof;
  };
  std::vector<OwnTail> own;
  for (const ChannelResidual& c : channels) {
    const bool any = std::any_of(c.line_correlation.begin(), c.line_correlation.end(), [](double r) { return r != 0; });
    std::optional<Eigen::VectorXd> lambda;
    if (any && w > 1) lambda = window_eigenvalues(w, c.line_correlation);
    if (lambda || c.sigma_dof > 0)
      own.push_back({static_cast<double>(c.f_hz.size()), lambda, c.sigma_dof});
    else
      independent_lines += static_cast<long>(c.f_hz.size());
  }
  if (own.empty()) return finding_threshold(options, independent_lines);
  // The expected number of windows above t: the independent lines' as in finding_threshold, plus each other
  // channel's lines times its windows' tail.
  return lowest_level(options, [&](double t) {
    double e = static_cast<double>(independent_lines) * independent_tail(w, t);
    for (const OwnTail& c : own) {
      const auto exact = [&](double x) { return c.lambda ? eigen_tail(*c.lambda, w, x) : independent_tail(w, x); };
      e += c.lines * window_tail(exact, t, c.dof);
    }
    return e;
  });
}

ResidualSummary analyse_residuals(const std::vector<ChannelResidual>& channels, const ResidualOptions& given) {
  ResidualSummary summary;
  ResidualOptions options = given;
  options.threshold = finding_threshold(given, channels);
  summary.threshold = options.threshold;
  double z_sum = 0;
  for (const ChannelResidual& original : channels) {
    const Eigen::Index n = static_cast<Eigen::Index>(original.f_hz.size());
    if (n == 0) continue;
    // A delay is one finding for the whole channel: when removing it explains most of the residual, report it
    // and look for bands in what it leaves. (A local mode also bends the phase, but a delay does not explain it.)
    auto normalized = [&](const Eigen::VectorXcd& measured) {
      Eigen::VectorXd z(n);
      for (Eigen::Index i = 0; i < n; ++i)
        z[i] = normalized_residual(measured[i], original.model[i], original.sigma[i]);
      return z;
    };
    Eigen::VectorXd z = normalized(original.measured);
    z_sum += z.sum();
    summary.lines += n;
    ChannelResidual c = original;
    Discrepancy trend;
    if (phase_trend(original, trend)) {
      Eigen::VectorXcd undelayed = original.measured;
      for (Eigen::Index i = 0; i < n; ++i)
        undelayed[i] *= std::exp(std::complex<double>(0, numerics::kTwoPi * trend.delay_s * original.f_hz[static_cast<std::size_t>(i)]));
      const Eigen::VectorXd z_undelayed = normalized(undelayed);
      if (z_undelayed.mean() <= 0.5 * z.mean()) {
        summary.discrepancies.push_back(trend);
        c.measured = undelayed;
        z = z_undelayed;
      }
    }
    const Eigen::VectorXcd smooth = smoothed(c.measured);
    const std::vector<int> data_peaks = magnitude_peaks(smooth), model_peaks = magnitude_peaks(c.model);
    for (const Band& band : significant_bands(z, options)) {
      summary.discrepancies.push_back(classify(c, smooth, band, data_peaks, model_peaks, options));
      for (Discrepancy& d : resonances_missing_in_band(c, smooth, z, band, data_peaks, model_peaks, options))
        summary.discrepancies.push_back(std::move(d));
      if (band.hi - band.lo + 1 < options.wide_band) continue;
      for (const Band& sub : contrasted_bands(z, band, options))
        if (sub.lo != band.lo || sub.hi != band.hi)
          summary.discrepancies.push_back(classify(c, smooth, sub, data_peaks, model_peaks, options));
    }
  }
  summary.mean_z = summary.lines ? z_sum / static_cast<double>(summary.lines) : 0;
  summary.discrepancies = merge_across_channels(std::move(summary.discrepancies));
  return summary;
}

}  // namespace mbgen
