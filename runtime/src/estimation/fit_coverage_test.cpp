// Do the FRF fit's error bars hold? Many noise realisations of mdof2's receptances (closed form, tests/support), each
// fitted from the truth; z = (estimate - truth) / reported std must have mean 0 (within its standard error) and RMS 1.
//
// The coherence column decides it. The fit weights a line by (1 - coh)/(n coh) |h|^2 with the measured h
// (frf_sigma.hpp): right for an analyser's coherence, |h|^2/(|h|^2 + s^2) from the same noisy estimate, whose
// (1 - coh)/coh |h|^2 = s^2 does not follow h's noise. A coherence from the noise-free response (what truthgen wrote
// until 2026-11-26) makes the weights sigma^2 |h|^2/|H|^2: lines whose noise shrank |h| weigh more, and m1 and k11
// came out about one std high. Both are checked: the first must be unbiased, the second must show the bias (so this
// test can see what it guards against).
#include "mbgen_test/estimation.hpp"

#include "mbgen/estimation/fit.hpp"
#include "mbgen/dynamics/parallel.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <random>
#include <vector>

using namespace mbgen;

namespace {

constexpr int kRealisations = 300;
constexpr int kEstimated = 7;  // m1, m2, k11, k22, k12, c11, c22 (c12 fixed)

enum class Coherence { Analyser, NoiseFree };

// mdof2's d1/F1 and d2/F1 on 10-400 Hz every 0.5 Hz with complex noise of 1 % of each channel's RMS |H| (40 dB, the
// noise of one measurement), and the coherence column of the given kind. Realisation i draws from its own seed.
FrfData realisation(int i, Coherence kind) {
  const test::Mdof2Values truth;
  std::mt19937 rng(static_cast<unsigned>(1000 + i));
  std::normal_distribution<double> normal;
  FrfData d;
  d.file = "mdof2 realisation " + std::to_string(i);
  d.f_hz = Eigen::VectorXd::LinSpaced(781, 10, 400);
  for (int c = 0; c < 2; ++c) {
    FrfChannel ch;
    ch.output = c == 0 ? "d1" : "d2";
    ch.input = "F1";
    Eigen::VectorXcd clean(d.f_hz.size());
    for (Eigen::Index k = 0; k < clean.size(); ++k)
      clean[k] = c == 0 ? test::mdof2_g11(truth, d.f_hz[k]) : test::mdof2_g21(truth, d.f_hz[k]);
    const double sigma = 0.01 * std::sqrt(clean.squaredNorm() / double(clean.size()));
    ch.values = clean;
    ch.coherence = Eigen::VectorXd(clean.size());
    for (Eigen::Index k = 0; k < clean.size(); ++k) {
      ch.values[k] += sigma / std::sqrt(2.0) * std::complex<double>(normal(rng), normal(rng));
      const double h2 = std::norm(kind == Coherence::Analyser ? ch.values[k] : clean[k]);
      (*ch.coherence)[k] = h2 / (h2 + sigma * sigma);
    }
    d.channels.push_back(ch);
  }
  return d;
}

struct Scatter {
  Eigen::VectorXd mean, rms;  // of z per parameter
};

Scatter scatter_of_z(Coherence kind) {
  const test::Mdof2Values truth;
  const Eigen::VectorXd p = (Eigen::VectorXd(kEstimated) << truth.m1, truth.m2, truth.k11, truth.k22, truth.k12,
                             truth.c11, truth.c22).finished();
  Eigen::MatrixXd z(kRealisations, kEstimated);
  parallel_for(kRealisations, 2, [&](std::size_t i) {
    const test::Mdof2Model model = test::mdof2_model(truth);
    FitOptions options;
    options.starts = 1;
    options.threads = 1;
    const FitResult r = fit(model, {DataSet(realisation(static_cast<int>(i), kind))}, options);
    for (int j = 0; j < kEstimated; ++j) {
      const ParameterEstimate& e = r.parameters[static_cast<std::size_t>(j)];
      z(static_cast<Eigen::Index>(i), j) = e.identifiable && e.std > 0 ? (e.value - p[j]) / e.std : 1e9;
    }
  });
  Scatter s;
  s.mean = z.colwise().mean().transpose();
  s.rms = (z.array().square().colwise().sum() / double(kRealisations)).sqrt().transpose();
  return s;
}

const char* const kNames[kEstimated] = {"m1", "m2", "k11", "k22", "k12", "c11", "c22"};

}  // namespace

TEST_CASE("FRF fit with an analyser's coherence: the reported std covers the scatter, no bias", "[fit][frf][coverage]") {
  const Scatter s = scatter_of_z(Coherence::Analyser);
  for (int j = 0; j < kEstimated; ++j) {
    const double standard_error = s.rms[j] / std::sqrt(double(kRealisations));
    INFO(kNames[j] << ": mean z " << s.mean[j] << " (standard error " << standard_error << "), RMS z " << s.rms[j]);
    CHECK(std::abs(s.mean[j]) < 3 * standard_error);
    // The RMS of 300 unit normals is 1 +- 0.04; the linearised std may be a little off as well.
    CHECK(s.rms[j] > 0.85);
    CHECK(s.rms[j] < 1.15);
  }
}

TEST_CASE("FRF fit with a coherence from the noise-free response: weights that follow the noise bias m1 and k11",
          "[fit][frf][coverage]") {
  const Scatter s = scatter_of_z(Coherence::NoiseFree);
  for (int j : {0, 2}) {  // m1, k11
    const double standard_error = s.rms[j] / std::sqrt(double(kRealisations));
    INFO(kNames[j] << ": mean z " << s.mean[j] << " (standard error " << standard_error << "), RMS z " << s.rms[j]);
    CHECK(s.mean[j] > 3 * standard_error);  // observed: m1 8, k11 6 standard errors
  }
}
