// The standard deviation of measured FRF values (frf_sigma.hpp): the H1 formula from the coherence, the floor, and
// a coherence printed with too few digits at a resonance far above the noise.
#include "mbgen/data/frf_sigma.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>

namespace {

using cd = std::complex<double>;

// A one-mode receptance on lines 80, 80.25, ... Hz: the mode at 90.83 Hz, 0.12 Hz wide, narrower than a line.
mbgen::FrfChannel narrow_mode(int lines) {
  mbgen::FrfChannel c;
  c.output = "d";
  c.input = "F";
  c.values.resize(lines);
  for (int k = 0; k < lines; ++k) {
    const double f = 80.0 + 0.25 * k, fn = 90.8285, zeta = 0.00065;
    const cd s(0, 2 * M_PI * f);
    const double w = 2 * M_PI * fn;
    c.values[k] = 1.0 / (s * s + 2 * zeta * w * s + w * w);
  }
  return c;
}

// The coherence an analyser reports when the output holds noise of power s2 the input does not explain,
// |h|^2 / (|h|^2 + s2), printed as a CSV prints it (six significant digits).
Eigen::VectorXd printed_coherence(const Eigen::VectorXcd& h, double s2) {
  Eigen::VectorXd g(h.size());
  for (Eigen::Index k = 0; k < h.size(); ++k) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", std::norm(h[k]) / (std::norm(h[k]) + s2));
    g[k] = std::strtod(text, nullptr);
  }
  return g;
}

}  // namespace

TEST_CASE("with coherence each line's variance is the H1 formula (1 - g2) / (n g2) |h|^2", "[frf_sigma]") {
  mbgen::FrfChannel c;
  c.values = Eigen::VectorXcd::Constant(12, cd(3.0, 4.0));  // |h| = 5
  c.coherence = Eigen::VectorXd::Constant(12, 0.8);
  const Eigen::VectorXd var = mbgen::frf_variance(c, 4, 1e-3);
  for (Eigen::Index k = 0; k < var.size(); ++k) CHECK(var[k] == Approx(0.2 / (0.8 * 4) * 25.0));
}

TEST_CASE("without coherence every line gets the channel's RMS |h|", "[frf_sigma]") {
  mbgen::FrfChannel c;
  c.values.resize(4);
  c.values << cd(1, 0), cd(0, 1), cd(1, 1), cd(-1, 1);
  const Eigen::VectorXd var = mbgen::frf_variance(c, 1, 1e-3);
  for (Eigen::Index k = 0; k < var.size(); ++k) CHECK(var[k] == Approx((1 + 1 + 2 + 2) / 4.0));
}

TEST_CASE("a coherence of exactly one gives the floor, not an infinite weight", "[frf_sigma]") {
  mbgen::FrfChannel c;
  c.values = Eigen::VectorXcd::Constant(9, cd(2.0, 0.0));
  c.coherence = Eigen::VectorXd::Constant(9, 1.0);
  const Eigen::VectorXd var = mbgen::frf_variance(c, 1, 1e-3);
  for (Eigen::Index k = 0; k < var.size(); ++k) CHECK(var[k] == Approx(std::pow(1e-3 * 2.0, 2)));
}

TEST_CASE("a coherence printed to six digits at a resonance 70 dB above the noise keeps the neighbours' noise level",
          "[frf_sigma]") {
  // The mdof2 control that read a false frequency shift: at the two lines beside a 0.12 Hz wide mode the printed
  // coherence is 1 (1 - g2 ~ 3e-7), and those lines got 100 times the weight the noise supports. The noise here is
  // the same at every line, so each line's variance must stay near it: at most 4 times, and at least a quarter of
  // its neighbours' (themselves printed with one or two digits of 1 - g2, up to 15 % low here), so at least 1/5.
  mbgen::FrfChannel c = narrow_mode(81);
  const double s2 = std::pow(c.values.cwiseAbs().maxCoeff() * std::pow(10.0, -70.0 / 20), 2);  // 70 dB below the peak
  c.coherence = printed_coherence(c.values, s2);
  int printed_one = 0;
  for (Eigen::Index k = 0; k < c.coherence->size(); ++k) printed_one += (*c.coherence)[k] == 1.0;
  REQUIRE(printed_one >= 2);  // the case is the one described above
  const Eigen::VectorXd var = mbgen::frf_variance(c, 1, 1e-3);
  for (Eigen::Index k = 0; k < var.size(); ++k) {
    INFO("line " << k << ", coherence " << (*c.coherence)[k] << ", variance / noise " << var[k] / s2);
    CHECK(var[k] >= 0.2 * s2);
    CHECK(var[k] <= 4.0 * s2);
  }
}

TEST_CASE("a single line whose coherence dips keeps its larger variance", "[frf_sigma]") {
  // The neighbourhood floor only raises a line's variance: a line where the noise really is larger (leakage at a
  // resonance, a mains line) keeps its own value.
  mbgen::FrfChannel c;
  c.values = Eigen::VectorXcd::Constant(21, cd(1.0, 0.0));
  c.coherence = Eigen::VectorXd::Constant(21, 0.99);
  (*c.coherence)[10] = 0.5;
  const Eigen::VectorXd var = mbgen::frf_variance(c, 1, 1e-3);
  CHECK(var[10] == Approx(1.0));
  CHECK(var[9] == Approx(0.01 / 0.99));
}
