// The noise level of measured FRFs from their own scatter: synthetic FRFs of a hand-written two-mode receptance
// with noise of known level added here, over several random draws.
#include "mbgen/data/frf_noise.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>

namespace {

using cd = std::complex<double>;
constexpr double two_pi = 6.283185307179586;

// A receptance with modes at f1 and f2 (damping ratios z1, z2), unit modal masses.
cd receptance(double f, double f1, double z1, double f2, double z2) {
  const cd s(0, two_pi * f);
  const auto mode = [&](double fn, double z) {
    const double w = two_pi * fn;
    return 1.0 / (s * s + 2.0 * z * w * s + w * w);
  };
  return mode(f1, z1) - 0.6 * mode(f2, z2);
}

struct Synthetic {
  Eigen::VectorXd f;
  Eigen::VectorXcd clean, noisy;
  Eigen::VectorXd sigma;  // the true standard deviation per line
};

// Lines f0 .. f0 + (n-1) df; noise of standard deviation additive * exp(drift x) + proportional * |H| per line
// (complex Gaussian, E|n|^2 = sigma^2).
Synthetic make(unsigned seed, int n, double df, double zeta, double additive_rel, double drift, double proportional) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Synthetic s;
  s.f.resize(n);
  s.clean.resize(n);
  s.noisy.resize(n);
  s.sigma.resize(n);
  for (int k = 0; k < n; ++k) {
    s.f[k] = 20.0 + df * k;
    s.clean[k] = receptance(s.f[k], 180.0, zeta, 410.0, 1.5 * zeta);
  }
  const double rms = std::sqrt(s.clean.cwiseAbs2().mean());
  const double mid = 0.5 * (s.f[0] + s.f[n - 1]), span = s.f[n - 1] - s.f[0];
  for (int k = 0; k < n; ++k) {
    const double add = additive_rel * rms * std::exp(0.5 * drift * (s.f[k] - mid) / span);
    s.sigma[k] = std::sqrt(add * add + std::pow(proportional * std::abs(s.clean[k]), 2));
    s.noisy[k] = s.clean[k] + s.sigma[k] / std::sqrt(2.0) * cd(normal(rng), normal(rng));
  }
  return s;
}

mbgen::FrfChannel channel(const Eigen::VectorXcd& values) {
  mbgen::FrfChannel c;
  c.output = "y";
  c.input = "u";
  c.values = values;
  return c;
}

// The largest ratio estimated/true or true/estimated over the lines.
double worst_ratio(const Eigen::VectorXd& estimated, const Eigen::VectorXd& truth) {
  double worst = 1;
  for (Eigen::Index k = 0; k < truth.size(); ++k)
    worst = std::max({worst, estimated[k] / truth[k], truth[k] / estimated[k]});
  return worst;
}

}  // namespace

TEST_CASE("frf_noise: additive white noise without coherence is found at its level everywhere", "[frf_noise]") {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Synthetic s = make(seed, 1200, 0.5, 0.02, 0.01, 0.0, 0.0);
    const mbgen::FrfNoise noise = mbgen::frf_noise(s.f, channel(s.noisy));
    INFO("seed " << seed << ": " << noise.description());
    CHECK(noise.source == mbgen::FrfNoise::Source::Scatter);
    // About 1200 lines determine the level to a few per cent; the peaks' curvature must not inflate it.
    CHECK(worst_ratio(noise.sigma, s.sigma) < 1.12);
  }
}

TEST_CASE("frf_noise: an additive level that drifts across the band is followed", "[frf_noise]") {
  for (unsigned seed = 21; seed <= 25; ++seed) {
    const Synthetic s = make(seed, 1500, 0.4, 0.02, 0.01, 3.0, 0.0);  // the level's variance changes e^3 = 20x
    const mbgen::FrfNoise noise = mbgen::frf_noise(s.f, channel(s.noisy));
    INFO("seed " << seed << ": " << noise.description());
    CHECK(noise.drift == Approx(3.0).margin(0.6));
    CHECK(worst_ratio(noise.sigma, s.sigma) < 1.2);
  }
}

TEST_CASE("frf_noise: lightly damped peaks a few lines wide do not inflate the level", "[frf_noise]") {
  // Half-power bandwidth 2 zeta f = 0.9 Hz at 180 Hz on 1 Hz lines: the response bends sharply over 2-3 lines.
  for (unsigned seed = 31; seed <= 35; ++seed) {
    const Synthetic s = make(seed, 1000, 1.0, 0.0025, 0.01, 0.0, 0.0);
    const mbgen::FrfNoise noise = mbgen::frf_noise(s.f, channel(s.noisy));
    INFO("seed " << seed << ": " << noise.description());
    CHECK(worst_ratio(noise.sigma, s.sigma) < 1.15);
    CHECK(noise.lines_left_out >= 2);  // the peak's lines were recognised as curvature
  }
}

// An FRF h averaged n times, noise of relative level `additive_rel`, with the coherence an analyser writes:
// |h|^2/(|h|^2 + s^2), s^2 the noise power of one average (the ordinary coherence does not fall with averaging; see
// frf_sigma.hpp for why it is the noisy h).
struct Averaged {
  Synthetic one;
  mbgen::FrfChannel channel;
  Eigen::VectorXd sigma;  // the true standard deviation of the averaged FRF per line
};

Averaged averaged(unsigned seed, double additive_rel, double n, int lines = 1200) {
  Averaged a{make(seed, lines, 600.0 / lines, 0.02, additive_rel, 0.0, 0.0), {}, {}};
  a.channel = channel(a.one.clean + (a.one.noisy - a.one.clean) / std::sqrt(n));
  a.channel.coherence = Eigen::VectorXd(a.one.clean.size());
  for (Eigen::Index k = 0; k < a.one.clean.size(); ++k) {
    const double h2 = std::norm(a.channel.values[k]);
    (*a.channel.coherence)[k] = h2 / (h2 + std::norm(a.one.sigma[k]));
  }
  a.sigma = a.one.sigma / std::sqrt(n);
  return a;
}

TEST_CASE("frf_noise: the number of averages behind a coherence-based level is found from the data's scatter",
          "[frf_noise]") {
  for (unsigned seed = 41; seed <= 45; ++seed) {
    const Averaged a = averaged(seed, 0.01, 50);
    const mbgen::FrfNoise noise = mbgen::frf_noise(a.one.f, a.channel);
    INFO("seed " << seed << ": " << noise.description());
    CHECK(noise.source == mbgen::FrfNoise::Source::Coherence);
    CHECK(noise.averages == Approx(50).epsilon(0.12));
    CHECK(noise.coherence_scale == Approx(1).epsilon(1e-4));
  }
}

TEST_CASE("frf_noise: where the coherence is low, the level follows the averaged noise, not one average's shape",
          "[frf_noise]") {
  // Noise at 30 % of the RMS response: the coherence falls to ~0.1 between and above the modes. Read with one
  // average's shape, (1 - coh^2) |h|^2 scaled to the lines of high coherence, the level there once came out ~3 times
  // too small at 50 averages.
  for (unsigned seed = 51; seed <= 54; ++seed) {
    for (double n : {1.0, 10.0, 50.0}) {
      const Averaged a = averaged(seed, 0.3, n, 4800);
      double lowest = 1;
      for (Eigen::Index k = 0; k < a.channel.coherence->size(); ++k) lowest = std::min(lowest, (*a.channel.coherence)[k]);
      REQUIRE(lowest < 0.15);
      const mbgen::FrfNoise noise = mbgen::frf_noise(a.one.f, a.channel);
      INFO("seed " << seed << ", " << n << " averages: " << noise.description());
      CHECK(noise.averages == Approx(n).epsilon(0.25));
      Eigen::VectorXd ratio = noise.sigma.cwiseQuotient(a.sigma);
      std::sort(ratio.data(), ratio.data() + ratio.size());
      CHECK(ratio[ratio.size() / 2] == Approx(1).epsilon(0.1));  // the median line
      CHECK(ratio[ratio.size() / 20] > 0.6);                       // 5 % of lines lower
      CHECK(ratio[ratio.size() - 1 - ratio.size() / 20] < 1.5);    // 5 % higher
    }
  }
}

// An analyser's H1 from `segments` averages, made here: each line's force spectra of unit magnitude and random
// phase (a periodic chirp's), the output the response plus complex noise of the one segment's level, h =
// sum(Y conj X) / sum|X|^2 and the coherence |sum(Y conj X)|^2 / (sum|X|^2 sum|Y|^2) from the same segments.
Averaged analyser(unsigned seed, double additive_rel, int segments, int lines = 2400) {
  Averaged a{make(seed, lines, 600.0 / lines, 0.02, additive_rel, 0.0, 0.0), {}, {}};
  std::mt19937_64 rng(seed + 1000);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> phase(0, two_pi);
  Eigen::VectorXcd h(lines);
  Eigen::VectorXd coherence(lines);
  for (int k = 0; k < lines; ++k) {
    cd cross = 0;
    double xx = 0, yy = 0;
    for (int m = 0; m < segments; ++m) {
      const cd x = std::polar(1.0, phase(rng));
      const cd y = a.one.clean[k] * x + a.one.sigma[k] / std::sqrt(2.0) * cd(normal(rng), normal(rng));
      cross += y * std::conj(x), xx += std::norm(x), yy += std::norm(y);
    }
    h[k] = cross / xx;
    coherence[k] = std::norm(cross) / (xx * yy);
  }
  a.channel = channel(h);
  a.channel.coherence = coherence;
  a.sigma = a.one.sigma / std::sqrt(static_cast<double>(segments));
  return a;
}

TEST_CASE("frf_noise: an analyser's coherence from few averages scatters, and its level says by how much",
          "[frf_noise]") {
  // (1 - coh^2)/coh^2 |h|^2 of 8 averages is a chi-square estimate of 14 degrees of freedom per line; five lines
  // pooled have 70. A coherence from the exact level (`averaged`) does not scatter.
  for (unsigned seed = 61; seed <= 63; ++seed) {
    const Averaged a = analyser(seed, 0.05, 8);
    const mbgen::FrfNoise noise = mbgen::frf_noise(a.one.f, a.channel);
    INFO("seed " << seed << ": " << noise.description() << ", level dof " << noise.level_dof);
    CHECK(noise.level_dof == Approx(70).epsilon(0.2));
    Eigen::VectorXd ratio = noise.sigma.cwiseQuotient(a.sigma);
    std::sort(ratio.data(), ratio.data() + ratio.size());
    CHECK(ratio[ratio.size() / 20] > 0.6);                     // pooled: 5 % of lines lower, not a tenth at 0.56
    CHECK(ratio[ratio.size() - 1 - ratio.size() / 20] < 1.4);  // 5 % higher
    const Averaged exact = averaged(seed, 0.05, 8);
    CHECK(mbgen::frf_noise(exact.one.f, exact.channel).level_dof == 0);
  }
}

TEST_CASE("frf_noise: too few lines fall back to the channel's RMS and say so", "[frf_noise]") {
  Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(5, 10, 14);
  const mbgen::FrfNoise noise = mbgen::frf_noise(f, channel(Eigen::VectorXcd::Constant(5, cd(3, 4))));
  CHECK(noise.source == mbgen::FrfNoise::Source::TooFewLines);
  CHECK(noise.sigma[0] == Approx(5.0));
  CHECK(noise.description().find("too few") != std::string::npos);
}
