#include "mbgen/data/frf_noise.hpp"

#include "mbgen/data/frf_sigma.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "text/string_format.hpp"

namespace mbgen {

namespace {

// Lines whose |d|^2 stands more than this many times above its fitted mean are taken as the response's own
// curvature, not noise: an exponential variable exceeds 6 times its mean once in 400 draws.
constexpr double kCut = 6.0;
// The mean of an exponential variable of mean 1 truncated at kCut: the fits below see only the lines under the
// cut, so their level comes out low by this factor.
const double kTruncatedMean = 1.0 - kCut * std::exp(-kCut) / (1.0 - std::exp(-kCut));

// Fourth differences d_k = h_{k-2} - 4 h_{k-1} + 6 h_k - 4 h_{k+1} + h_{k+2}: they cancel any cubic through five
// lines, so a resonance a few lines wide bends them far less than second differences (by the square of its
// half-width in lines), while white noise passes with E|d|^2 = 1 + 16 + 36 + 16 + 1 = 70 times its variance.
constexpr int kHalf = 2;
constexpr double kWeights[] = {1, -4, 6, -4, 1};

struct Stencil {
  Eigen::VectorXd e;  // |d_k|^2, k = kHalf .. n-1-kHalf (index k - kHalf)
};

Stencil differences(const Eigen::VectorXcd& h) {
  const Eigen::Index m = h.size() - 2 * kHalf;
  Stencil s;
  s.e.resize(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    std::complex<double> d = 0;
    for (int j = 0; j <= 2 * kHalf; ++j) d += kWeights[j] * h[k + j];
    s.e[k] = std::norm(d);
  }
  return s;
}

// The stencil's sum of a per-line variance v: sum_j w_j^2 v_{k+j}.
Eigen::VectorXd stencil_sum(const Eigen::VectorXd& v) {
  const Eigen::Index m = v.size() - 2 * kHalf;
  Eigen::VectorXd out(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    double sum = 0;
    for (int j = 0; j <= 2 * kHalf; ++j) sum += kWeights[j] * kWeights[j] * v[k + j];
    out[k] = sum;
  }
  return out;
}

struct LevelFit {
  double a = 0, log_likelihood = -std::numeric_limits<double>::infinity();
};

// Maximum likelihood of e_k ~ Exp(mean a G_k) over the lines `kept`: a = mean(e_k / G_k). The kept lines are those
// under kCut times their mean, so their mean is kTruncatedMean times the fitted one; that bias is removed. The
// log-likelihood is over the kept lines, so that fits compared on the same lines compare fairly.
LevelFit fit_level(const Eigen::VectorXd& e, const Eigen::VectorXd& G, const std::vector<char>& kept) {
  double sum = 0;
  int count = 0;
  for (Eigen::Index k = 0; k < e.size(); ++k)
    if (kept[static_cast<std::size_t>(k)]) sum += e[k] / G[k], ++count;
  LevelFit fit;
  fit.a = count > 0 ? std::max(sum / count / kTruncatedMean, 1e-300) : 1e-300;
  fit.log_likelihood = 0;
  for (Eigen::Index k = 0; k < e.size(); ++k) {
    if (!kept[static_cast<std::size_t>(k)]) continue;
    const double mean = std::max(fit.a * G[k], 1e-300);
    fit.log_likelihood -= std::log(mean) + e[k] / mean;
  }
  return fit;
}

FrfNoise from_scatter(const Eigen::VectorXd& f_hz, const Eigen::VectorXcd& h, double floor) {
  const Eigen::Index n = h.size();
  const Stencil s = differences(h);
  const double span = std::max(f_hz[n - 1] - f_hz[0], 1e-300), mid = 0.5 * (f_hz[n - 1] + f_hz[0]);
  Eigen::VectorXd x(n);
  for (Eigen::Index k = 0; k < n; ++k) x[k] = (f_hz[k] - mid) / span;
  // Which lines are noise: first under a constant level, then under the best model so far. Within one pass every
  // drift is scored on the same lines; the drift by a coarse search, then refined.
  const Eigen::Index m = s.e.size();
  std::vector<char> kept(static_cast<std::size_t>(m), 1);
  const auto drift_weights = [&](double g) { return stencil_sum(x.unaryExpr([g](double v) { return std::exp(g * v); })); };
  const auto trim = [&](const Eigen::VectorXd& G, double a) {
    int left_out = 0;
    for (Eigen::Index k = 0; k < m; ++k) {
      kept[static_cast<std::size_t>(k)] = s.e[k] <= kCut * a * G[k];
      left_out += !kept[static_cast<std::size_t>(k)];
    }
    return left_out;
  };
  const Eigen::VectorXd flat = drift_weights(0);
  for (int pass = 0; pass < 10; ++pass) {
    const std::vector<char> before = kept;
    trim(flat, fit_level(s.e, flat, kept).a);
    if (kept == before) break;
  }
  double best_g = 0;
  LevelFit best;
  int left_out = 0;
  for (int pass = 0; pass < 4; ++pass) {
    best = LevelFit{};
    const auto try_drift = [&](double g) {
      const LevelFit fit = fit_level(s.e, drift_weights(g), kept);
      if (fit.log_likelihood > best.log_likelihood) best = fit, best_g = g;
    };
    for (int g = -8; g <= 8; g += 2) try_drift(g);
    const double coarse = best_g;
    for (double g = coarse - 1.75; g <= coarse + 1.75 + 1e-9; g += 0.25)
      if (g != coarse) try_drift(g);
    const std::vector<char> before = kept;
    left_out = trim(drift_weights(best_g), best.a);
    if (kept == before) break;
  }

  FrfNoise out;
  out.source = FrfNoise::Source::Scatter;
  out.additive = best.a;
  out.drift = best_g;
  out.lines_left_out = left_out;
  const double rms = std::sqrt(h.cwiseAbs2().mean());
  out.sigma.resize(n);
  for (Eigen::Index k = 0; k < n; ++k)
    out.sigma[k] = std::max(std::sqrt(best.a * std::exp(best_g * x[k])), floor * rms);
  return out;
}

// The degrees of freedom at which one line's coherence-based level is taken as exact: chi-square of 200 scatters by
// 10 % (sqrt(2/200)), which moves a five-line window's tail at the threshold by far less than the windows judged do.
constexpr double kExactLineDof = 200;

// v averaged over the five lines around each line (fewer at the ends).
Eigen::VectorXd five_line_mean(const Eigen::VectorXd& v) {
  const Eigen::Index n = v.size();
  Eigen::VectorXd out(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, k - 2), hi = std::min<Eigen::Index>(n - 1, k + 2);
    out[k] = v.segment(lo, hi - lo + 1).mean();
  }
  return out;
}

// The degrees of freedom nu of one line's variance estimate v_k, from its scatter about its four neighbours' mean:
// r_k = v_k / mean(v_k-2, v_k-1, v_k+1, v_k+2) is F(nu, 4 nu)-distributed where v is a chi-square estimate of a
// smooth level, whose variance 2 (4 nu)^2 (5 nu - 2) / (nu (4 nu - 2)^2 (4 nu - 4)) is matched to the mean of
// (r_k - 1)^2 over the stencils `usable` marks (centred two lines on). 0 where v does not scatter: a coherence
// made from the exact noise level (test data) gives it exactly, up to its printed digits, and a level that follows
// the response instead of a smooth one only lowers nu (a conservative threshold).
double line_dof(const Eigen::VectorXd& v, const std::vector<char>& usable) {
  double sum = 0;
  long count = 0;
  for (std::size_t k = 0; k < usable.size(); ++k) {
    if (!usable[k]) continue;
    const auto c = static_cast<Eigen::Index>(k) + 2;
    const double neighbours = (v[c - 2] + v[c - 1] + v[c + 1] + v[c + 2]) / 4;
    if (!(neighbours > 0)) continue;
    const double r = v[c] / neighbours - 1;
    sum += r * r, ++count;
  }
  if (count < FrfNoise::kMinLines) return 0;
  const double m = sum / static_cast<double>(count);
  const auto f_variance = [](double nu) {
    const double d2 = 4 * nu;
    return 2 * d2 * d2 * (nu + d2 - 2) / (nu * (d2 - 2) * (d2 - 2) * (d2 - 4));
  };
  if (!(m > f_variance(1e9))) return 0;  // no scatter beyond the digits: exact
  double lo = 2, hi = 1e9;                // f_variance falls with nu
  if (m >= f_variance(lo)) return lo;
  for (int i = 0; i < 100 && hi > lo * (1 + 1e-9); ++i) {
    const double mid = std::sqrt(lo * hi);
    (f_variance(mid) > m ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

// The coherence-based level: the variance of the H1 estimate, (1 - coh^2)/(n coh^2) |h|^2 with the measured |h|, the
// fit's own formula (frf_variance, frf_sigma.hpp, which says why the measured |h|), with the number of averages n
// estimated from the data: it is rarely known, and it sets the level's scale. n is estimated from the data's scatter
// on the lines where the response stands out of the noise (coherence 0.8 and up), where the coherence itself is well
// determined: the n at which the scatter's maximum-likelihood scale is one. Where the scatter exceeds even one
// average's level (a coherence too optimistic), n stays 1 and the level is scaled up to the scatter.
// (Until 2026-11-26 the test data's coherence came from the noise-free response, not the noisy h; this level then
// averaged |h|^2 over five lines and corrected its bias, (1 - coh^2)|h|^2/(n coh^2 + 1 - coh^2). With an
// analyser's coherence, (1 - coh^2)/coh^2 |h|^2 is the residual power itself, and that correction made the level
// too small by up to 2 where the coherence is low.)
FrfNoise from_coherence(const FrfChannel& channel, double floor) {
  const Eigen::VectorXcd& h = channel.values;
  const Eigen::VectorXd& coherence = *channel.coherence;
  const Stencil s = differences(h);
  const Eigen::Index m = s.e.size();
  std::vector<char> usable(static_cast<std::size_t>(m), 0);
  int usable_count = 0;
  for (Eigen::Index k = 0; k < m; ++k) {
    bool clear = true;
    for (int j = 0; j <= 2 * kHalf; ++j) clear = clear && coherence[k + j] >= 0.8;
    usable[static_cast<std::size_t>(k)] = clear;
    usable_count += clear;
  }
  if (usable_count < FrfNoise::kMinLines) std::fill(usable.begin(), usable.end(), 1);  // too few: use all
  // One line's level scattering by under 10 % (nu >= 200) is taken as exact, line by line: pooled, it would only
  // blur a level that may follow the response. Otherwise five lines are pooled, with five times the freedom.
  const double nu = line_dof(frf_variance(channel, 1, floor), usable);
  const bool pooled = nu > 0 && nu < kExactLineDof;
  const auto variance = [&](double averages) {
    const Eigen::VectorXd v = frf_variance(channel, averages, floor);
    return pooled ? five_line_mean(v) : v;
  };
  // Maximum likelihood of the scale of e_k ~ Exp(scale V_k), V the stencil sum of variance v, the
  // curvature-dominated lines left out.
  int left_out = 0;
  const auto ml_scale = [&](const Eigen::VectorXd& v_lines) {
    const Eigen::VectorXd v = stencil_sum(v_lines);
    double scale = 1;
    for (int iteration = 0; iteration < 40; ++iteration) {
      double sum = 0;
      int kept = 0;
      for (Eigen::Index k = 0; k < m; ++k)
        if (usable[static_cast<std::size_t>(k)] && s.e[k] <= kCut * scale * v[k]) sum += s.e[k] / v[k], ++kept;
      const double next = kept > 0 ? sum / kept / kTruncatedMean : scale;
      left_out = usable_count - kept;
      const bool settled = std::abs(next - scale) <= 1e-9 * scale;
      scale = next;
      if (settled) break;
    }
    return scale;
  };
  // The scale rises with n (the level shrinks like 1/n); find where it is one, on a logarithmic bisection.
  double averages = 1;
  if (ml_scale(variance(1)) < 1) {
    double lo = 1, hi = 2;
    while (ml_scale(variance(hi)) < 1 && hi < 1e12) lo = hi, hi *= 2;
    for (int iteration = 0; iteration < 60 && hi > lo * (1 + 1e-6); ++iteration) {
      const double mid = std::sqrt(lo * hi);
      (ml_scale(variance(mid)) < 1 ? lo : hi) = mid;
    }
    averages = std::sqrt(lo * hi);
  }
  const Eigen::VectorXd v = variance(averages);
  const double scale = ml_scale(v);
  FrfNoise out;
  out.source = FrfNoise::Source::Coherence;
  out.averages = averages;
  out.coherence_scale = scale;
  out.level_dof = pooled ? 5 * nu : 0;
  out.lines_left_out = std::max(left_out, 0);
  out.sigma = (scale * v.array()).sqrt();
  return out;
}

}  // namespace

std::string FrfNoise::description() const {
  switch (source) {
    case Source::Coherence:
      if (averages > 1) {
        std::string text = detail::format("coherence, for an FRF averaged %.3g times (the number that matches the "
                                          "data's scatter between neighbouring lines)",
                                          averages);
        if (level_dof > 0)
          text += detail::format(", over five lines: the coherence scatters, the level has %.0f degrees of freedom",
                                 level_dof);
        return text;
      }
      return detail::format("coherence, its variance scaled by %.3g to match the data's scatter between neighbouring "
                            "lines (larger than one average's)",
                            coherence_scale);
    case Source::Scatter:
      return detail::format("the data's scatter between neighbouring lines (no coherence): %.3g at the band's centre, "
                            "its variance changing by a factor %.3g across the band",
                            std::sqrt(additive), std::exp(drift));
    case Source::TooFewLines:
      break;
  }
  return "too few lines to estimate it: the channel's RMS";
}

FrfNoise frf_noise(const Eigen::VectorXd& f_hz, const FrfChannel& channel) {
  const double floor = FrfWeighting{}.floor;  // the fit's: no line weighs more than its floor allows
  const Eigen::VectorXcd& h = channel.values;
  const Eigen::Index n = h.size();
  if (n < FrfNoise::kMinLines) {
    FrfNoise out;
    out.source = FrfNoise::Source::TooFewLines;
    const double rms = n > 0 ? std::sqrt(h.cwiseAbs2().mean()) : 1.0;
    out.sigma = Eigen::VectorXd::Constant(n, rms > 0 ? rms : 1.0);
    return out;
  }
  if (channel.coherence) return from_coherence(channel, floor);
  return from_scatter(f_hz, h, floor);
}

}  // namespace mbgen
