// Welch H1 against exact frequency responses of systems simulated here with their own difference
// equations: noise-free (coherence ~ 1), with output noise (error and coherence as statistics predicts),
// two correlated inputs (MIMO H1), and a zero-order-held continuous system (hold compensation).
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <random>
#include <thread>

#include "mbgen/data/data_error.hpp"
#include "mbgen/data/welch.hpp"

using namespace mbgen;
using cd = std::complex<double>;

namespace {

// y[k] = b0 u[k] + b1 u[k-1] + b2 u[k-2] - a1 y[k-1] - a2 y[k-2]
struct SecondOrder {
  double b0, b1, b2, a1, a2;
  Eigen::VectorXd filter(const Eigen::VectorXd& u) const {
    Eigen::VectorXd y(u.size());
    double u1 = 0, u2 = 0, y1 = 0, y2 = 0;
    for (Eigen::Index k = 0; k < u.size(); ++k) {
      y[k] = b0 * u[k] + b1 * u1 + b2 * u2 - a1 * y1 - a2 * y2;
      u2 = u1;
      u1 = u[k];
      y2 = y1;
      y1 = y[k];
    }
    return y;
  }
  // Exact response at frequency f (Hz) for sample interval dt: B(z)/A(z), z = exp(i 2 pi f dt).
  cd response(double f, double dt) const {
    const cd zi = std::polar(1.0, -2 * M_PI * f * dt);  // z^-1
    return (b0 + b1 * zi + b2 * zi * zi) / (1.0 + a1 * zi + a2 * zi * zi);
  }
};

// Poles r exp(+-i theta): a resonance at theta / (2 pi dt) Hz.
SecondOrder resonator(double r, double theta, double b0, double b1, double b2) {
  return {b0, b1, b2, -2 * r * std::cos(theta), r * r};
}

Eigen::VectorXd white_noise(Eigen::Index n, unsigned seed, double sigma = 1.0) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> dist(0.0, sigma);
  Eigen::VectorXd v(n);
  for (Eigen::Index k = 0; k < n; ++k) v[k] = dist(gen);
  return v;
}

TimeRecord make_record(double dt, std::vector<Signal> signals, HoldMode hold = HoldMode::None) {
  TimeRecord r;
  r.file = "synthetic";
  r.hold = hold;
  const Eigen::Index n = signals.front().values.size();
  r.t = Eigen::VectorXd::LinSpaced(n, 0.0, dt * static_cast<double>(n - 1));
  r.signals = std::move(signals);
  return r;
}

constexpr double kDt = 1e-3;
constexpr Eigen::Index kSamples = 1 << 18;
constexpr Eigen::Index kSegment = 1024;

}  // namespace

TEST_CASE("Welch H1, one input, no noise: exact response and coherence ~ 1") {
  const SecondOrder sys = resonator(0.9, 2 * M_PI * 0.1, 1.0, 0.5, 0.2);
  const Eigen::VectorXd u = white_noise(kSamples, 1);
  const TimeRecord rec = make_record(kDt, {{"F", u}, {"x", sys.filter(u)}});
  WelchOptions opt;
  opt.segment_length = kSegment;
  const WelchEstimate est = welch_h1(rec, {"F"}, {"x"}, opt);
  CHECK(est.segments == 1 + (kSamples - kSegment) / (kSegment / 2));
  CHECK(est.dropped_bins.empty());
  REQUIRE(est.frf.f_hz.size() == kSegment / 2 + 1);
  CHECK(est.frf.f_hz[1] == Approx(1.0 / (kSegment * kDt)));
  CHECK(est.frf.f_hz[kSegment / 2] == Approx(0.5 / kDt));
  REQUIRE(est.frf.channels.size() == 1);
  const FrfChannel& h = est.frf.channels[0];
  CHECK(h.output == "x");
  CHECK(h.input == "F");
  // Two error sources without noise (Bendat & Piersol, ch. 8/9):
  // - bias: H1 is the true FRF smoothed by the window's power spectrum (variance 1/3 bin^2 for Hann); at a
  //   resonance of half-power half-width B bins the relative bias is about (1/3) / B^2, B = (1 - r) L / (2 pi);
  // - scatter: the response to input before a segment acts as uncorrelated output noise; it lowers the
  //   coherence to g2 and leaves a random error of sqrt((1 - g2) / (g2 n_d)), n_d ~ segments / 1.06.
  const double half_width = (1 - 0.9) * static_cast<double>(kSegment) / (2 * M_PI);
  const double bias = (1.0 / 3.0) / (half_width * half_width);
  const double n_d = static_cast<double>(est.segments) / 1.06;
  double worst = 0, min_coherence = 1, mean_coherence = 0;
  int outside = 0;
  for (Eigen::Index k = 0; k < est.frf.f_hz.size(); ++k) {
    const cd exact = sys.response(est.frf.f_hz[k], kDt);
    const double g2 = (*h.coherence)[k];
    const double error = std::abs(h.values[k] - exact) / std::abs(exact);
    if (error > 1.5 * bias + 4 * std::sqrt((1 - g2) / (g2 * n_d))) ++outside;
    worst = std::max(worst, error);
    min_coherence = std::min(min_coherence, g2);
    mean_coherence += g2 / static_cast<double>(est.frf.f_hz.size());
  }
  INFO("worst relative error " << worst << " (predicted bias at the peak " << bias << "), coherence >= "
                               << min_coherence << ", mean " << mean_coherence);
  CHECK(outside == 0);
  CHECK(worst < 5e-3);
  // Coherence ~ 1: the deficit is of the order of the decay time over the segment length (10 / 1024).
  CHECK(min_coherence > 0.99);
  CHECK(mean_coherence > 0.999);

  // Hamming works alike; a rectangular window leaks more but still converges.
  opt.window = WelchWindow::Hamming;
  const WelchEstimate hamming = welch_h1(rec, {"F"}, {"x"}, opt);
  const Eigen::Index peak = static_cast<Eigen::Index>(std::lround(0.1 * kSegment));
  CHECK(std::abs(hamming.frf.channels[0].values[peak] - sys.response(hamming.frf.f_hz[peak], kDt)) <
        5e-3 * std::abs(sys.response(hamming.frf.f_hz[peak], kDt)));
}

TEST_CASE("Welch H1, output noise: errors and coherence as statistics predicts") {
  const SecondOrder sys = resonator(0.9, 2 * M_PI * 0.1, 1.0, 0.5, 0.2);
  const double sigma_u = 1.0, sigma_n = 1.0;
  const Eigen::VectorXd u = white_noise(kSamples, 2, sigma_u);
  const Eigen::VectorXd y = sys.filter(u) + white_noise(kSamples, 3, sigma_n);
  const TimeRecord rec = make_record(kDt, {{"F", u}, {"x", y}});
  WelchOptions opt;
  opt.segment_length = kSegment;
  const WelchEstimate est = welch_h1(rec, {"F"}, {"x"}, opt);
  const FrfChannel& h = est.frf.channels[0];
  // Theory (Bendat & Piersol): for white input and white output noise the true coherence is
  // g2 = |H|^2 su^2 / (|H|^2 su^2 + sn^2), and E|H1 - H|^2 / |H|^2 = (1 - g2) / (g2 n_d) with n_d the
  // number of independent averages (50 % overlapping Hann segments: about segments / 1.06).
  const double n_d = static_cast<double>(est.segments) / 1.06;
  double normalized_error = 0, coherence_bias = 0, min_g2 = 1, max_g2 = 0;
  int bins = 0;
  for (Eigen::Index k = 1; k + 1 < est.frf.f_hz.size(); ++k) {
    const cd exact = sys.response(est.frf.f_hz[k], kDt);
    const double power = std::norm(exact) * sigma_u * sigma_u;
    const double g2 = power / (power + sigma_n * sigma_n);
    min_g2 = std::min(min_g2, g2);
    max_g2 = std::max(max_g2, g2);
    normalized_error += std::norm(h.values[k] - exact) / (std::norm(exact) * (1 - g2) / (g2 * n_d));
    coherence_bias += (*h.coherence)[k] - g2;
    ++bins;
  }
  normalized_error /= bins;
  coherence_bias /= bins;
  INFO("coherence range of the test " << min_g2 << " .. " << max_g2 << "; mean normalized squared error "
                                      << normalized_error << "; mean coherence bias " << coherence_bias);
  REQUIRE(min_g2 < 0.3);  // the test covers poor and good coherence
  REQUIRE(max_g2 > 0.99);
  // Mean of ~510 chi-square-like ratios with expectation 1: well within [0.8, 1.25].
  CHECK(normalized_error > 0.8);
  CHECK(normalized_error < 1.25);
  // The coherence estimate is biased upwards by about (1 - g2)^2 / n_d < 0.004: the mean stays close.
  CHECK(std::abs(coherence_bias) < 0.01);
  for (Eigen::Index k = 0; k < est.frf.f_hz.size(); ++k) CHECK((*h.coherence)[k] < 1.0);
  // The variance the estimate reports for itself: the same statistics without knowing the exact response, with the
  // overlap's ~segments / 1.06 independent averages (the ratio's mean is ~1; it read ~1.06 with n = segments).
  REQUIRE(est.variance.size() == 1);
  double reported = 0;
  for (Eigen::Index k = 1; k + 1 < est.frf.f_hz.size(); ++k)
    reported += std::norm(h.values[k] - sys.response(est.frf.f_hz[k], kDt)) / est.variance[0][k];
  reported /= bins;
  INFO("mean squared error over reported variance " << reported);
  CHECK(reported > 0.85);
  CHECK(reported < 1.35);
}

TEST_CASE("Welch H1, two correlated inputs and output noise: the reported variance of each path") {
  // With correlated inputs a path's variance grows by [Gxx^-1]_ii Gxx_ii = 1 / (1 - rho^2), here about 1.5: a
  // single-input formula would be too small by that factor.
  const SecondOrder s1 = resonator(0.9, 2 * M_PI * 0.08, 1.0, 0.0, 0.0);
  const SecondOrder s2 = resonator(0.9, 2 * M_PI * 0.2, 0.5, -0.3, 0.0);
  const Eigen::VectorXd u1 = white_noise(kSamples, 6);
  const Eigen::VectorXd u2 = white_noise(kSamples, 7) + 0.7 * u1;
  const Eigen::VectorXd y = s1.filter(u1) + s2.filter(u2) + white_noise(kSamples, 8, 2.0);
  const TimeRecord rec = make_record(kDt, {{"u1", u1}, {"u2", u2}, {"y", y}});
  WelchOptions opt;
  opt.segment_length = kSegment;
  const WelchEstimate est = welch_h1(rec, {"u1", "u2"}, {"y"}, opt);
  REQUIRE(est.variance.size() == 2);
  const SecondOrder* exact[2] = {&s1, &s2};
  for (int i = 0; i < 2; ++i) {
    double ratio = 0;
    int bins = 0;
    for (Eigen::Index k = 1; k + 1 < est.frf.f_hz.size(); ++k, ++bins)
      ratio += std::norm(est.frf.channels[i].values[k] - exact[i]->response(est.frf.f_hz[k], kDt)) / est.variance[i][k];
    ratio /= bins;
    INFO("path " << i << ": mean squared error over reported variance " << ratio);
    CHECK(ratio > 0.85);
    CHECK(ratio < 1.35);
  }
}

TEST_CASE("Welch H1, two correlated inputs: MIMO H1 and multiple coherence") {
  const SecondOrder s11 = resonator(0.9, 2 * M_PI * 0.08, 1.0, 0.0, 0.0);
  const SecondOrder s12 = resonator(0.9, 2 * M_PI * 0.2, 0.5, -0.3, 0.0);
  const SecondOrder s21 = {0.3, 0.2, 0.1, 0.0, 0.0};  // FIR
  const SecondOrder s22 = resonator(0.85, 2 * M_PI * 0.3, 1.0, 1.0, 0.0);
  const Eigen::VectorXd u1 = white_noise(kSamples, 4);
  // The second input shares part of the first: H1 must undo the correlation through Gxx^{-1}.
  const Eigen::VectorXd u2 = white_noise(kSamples, 5) + 0.7 * u1;
  const Eigen::VectorXd y1 = s11.filter(u1) + s12.filter(u2);
  const Eigen::VectorXd y2 = s21.filter(u1) + s22.filter(u2);
  const TimeRecord rec = make_record(kDt, {{"y2", y2}, {"u1", u1}, {"y1", y1}, {"u2", u2}});
  WelchOptions opt;
  opt.segment_length = kSegment;
  const WelchEstimate est = welch_h1(rec, {"u1", "u2"}, {"y1", "y2"}, opt);
  REQUIRE(est.frf.channels.size() == 4);
  const SecondOrder* exact[2][2] = {{&s11, &s12}, {&s21, &s22}};
  const char* out_names[] = {"y1", "y2"};
  const char* in_names[] = {"u1", "u2"};
  for (int o = 0; o < 2; ++o)
    for (int i = 0; i < 2; ++i) {
      const FrfChannel* h = est.frf.find(out_names[o], in_names[i]);
      REQUIRE(h);
      double worst = 0, min_coherence = 1;
      for (Eigen::Index k = 0; k < est.frf.f_hz.size(); ++k) {
        const cd e = exact[o][i]->response(est.frf.f_hz[k], kDt);
        worst = std::max(worst, std::abs(h->values[k] - e));
        min_coherence = std::min(min_coherence, (*h->coherence)[k]);
      }
      // The error of one path reaches the others through the input correlation (u2 holds 0.7 u1), so it
      // is measured against the output's largest response, not the path's own.
      double peak = 0;
      for (int j = 0; j < 2; ++j)
        for (Eigen::Index k = 0; k < est.frf.f_hz.size(); ++k)
          peak = std::max(peak, std::abs(exact[o][j]->response(est.frf.f_hz[k], kDt)));
      INFO(out_names[o] << "/" << in_names[i] << ": worst error " << worst / peak << " of the output's peak, "
                        << "multiple coherence >= " << min_coherence);
      CHECK(worst < 5e-3 * peak);
      CHECK(min_coherence > 0.99);
    }
  // Order of channels: outputs outer, inputs inner.
  CHECK(est.frf.channels[1].output == "y1");
  CHECK(est.frf.channels[1].input == "u2");
}

TEST_CASE("Welch H1 of a zero-order-held continuous system: the hold's half-sample delay") {
  // x' = -a x + b u with u held over each sample: exact discretization x[k+1] = e x[k] + (1 - e) b/a u[k],
  // e = exp(-a dt). Its continuous FRF is G(s) = b / (s + a).
  const double a = 2 * M_PI * 20, b = a, dt = 1e-3;
  const double e = std::exp(-a * dt);
  const Eigen::VectorXd u = white_noise(kSamples, 6);
  Eigen::VectorXd x(u.size());
  double state = 0;
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    x[k] = state;
    state = e * state + (1 - e) * b / a * u[k];
  }
  const TimeRecord rec = make_record(dt, {{"F", u}, {"x", x}}, HoldMode::ZeroOrder);
  WelchOptions opt;
  opt.segment_length = kSegment;
  const WelchEstimate raw = welch_h1(rec, {"F"}, {"x"}, opt);
  opt.compensate_hold = true;
  const WelchEstimate compensated = welch_h1(rec, {"F"}, {"x"}, opt);
  double worst_raw = 0, worst_compensated = 0;
  for (Eigen::Index k = 1; k < raw.frf.f_hz.size(); ++k) {
    const double f = raw.frf.f_hz[k];
    if (f > 50) break;  // up to 5 % of the sampling rate, where aliasing is small
    const cd g = b / (cd(0, 2 * M_PI * f) + a);
    worst_raw = std::max(worst_raw, std::abs(raw.frf.channels[0].values[k] - g) / std::abs(g));
    worst_compensated = std::max(worst_compensated, std::abs(compensated.frf.channels[0].values[k] - g) / std::abs(g));
  }
  INFO("raw " << worst_raw << ", compensated " << worst_compensated);
  CHECK(worst_raw > 0.1);             // the half-sample delay: pi f dt = 0.157 rad at 50 Hz
  CHECK(worst_compensated < 0.02);    // what remains is aliasing, O((a dt)^2)
  // A record without hold is left alone even when compensation is asked for.
  TimeRecord unheld = rec;
  unheld.hold = HoldMode::None;
  CHECK(welch_h1(unheld, {"F"}, {"x"}, opt).frf.channels[0].values == raw.frf.channels[0].values);
}

TEST_CASE("zero-order hold response") {
  CHECK(zero_order_hold_response(0, 1e-3) == cd(1, 0));
  // At Nyquist: magnitude 2/pi, phase -pi/2.
  const cd nyquist = zero_order_hold_response(500, 1e-3);
  CHECK(std::abs(nyquist) == Approx(2 / M_PI));
  CHECK(std::arg(nyquist) == Approx(-M_PI / 2));
}

TEST_CASE("Welch H1 errors") {
  const Eigen::VectorXd u = white_noise(100, 7);
  const TimeRecord rec = make_record(kDt, {{"F", u}, {"x", u}, {"G", u}});
  WelchOptions opt;
  opt.segment_length = 64;
  CHECK_THROWS_WITH(welch_h1(rec, {"F"}, {"y"}, opt), Catch::Contains("no signal 'y'"));
  opt.segment_length = 128;
  CHECK_THROWS_WITH(welch_h1(rec, {"F"}, {"x"}, opt), Catch::Contains("fewer than one Welch segment of 128"));
  opt.segment_length = 64;
  opt.overlap = 1.0;
  CHECK_THROWS_WITH(welch_h1(rec, {"F"}, {"x"}, opt), Catch::Contains("overlap must be in [0, 1)"));
  opt.overlap = 0.0;
  CHECK_THROWS_WITH(welch_h1(rec, {"F", "G"}, {"x"}, opt), Catch::Contains("needs at least as many segments"));
  CHECK_THROWS_AS(welch_h1(rec, {}, {"x"}, opt), DataError);
  // Identical inputs: the input spectral matrix is singular in every bin, all bins are dropped.
  opt.segment_length = 32;
  const WelchEstimate same = welch_h1(rec, {"F", "G"}, {"x"}, opt);
  CHECK(same.frf.f_hz.size() == 0);
  CHECK(same.dropped_bins.size() == 17);
}

TEST_CASE("Welch H1 from several threads gives the sequential result") {
  const SecondOrder sys = resonator(0.9, 2 * M_PI * 0.1, 1.0, 0.5, 0.2);
  const Eigen::VectorXd u = white_noise(1 << 14, 8);
  const TimeRecord rec = make_record(kDt, {{"F", u}, {"x", sys.filter(u)}});
  std::vector<Eigen::VectorXcd> results(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < results.size(); ++i)
    threads.emplace_back([&, i] {
      WelchOptions opt;
      opt.segment_length = 128 << i;  // different lengths: every thread plans its own transform
      results[i] = welch_h1(rec, {"F"}, {"x"}, opt).frf.channels[0].values;
    });
  for (auto& t : threads) t.join();
  for (std::size_t i = 0; i < results.size(); ++i) {
    WelchOptions opt;
    opt.segment_length = 128 << i;
    CHECK(results[i] == welch_h1(rec, {"F"}, {"x"}, opt).frf.channels[0].values);
  }
}

TEST_CASE("Welch H1's noise correlates between neighbouring lines as the window says") {
  WelchOptions opt;
  opt.segment_length = kSegment;
  const std::vector<double> rho = welch_line_correlation(opt, 2);
  REQUIRE(rho.size() == 2);
  CHECK(rho[0] == Approx(4.0 / 9.0).margin(1e-12));  // Hann: (2/3)^2
  CHECK(rho[1] == Approx(1.0 / 36.0).margin(1e-12));  // (1/6)^2
  opt.window = WelchWindow::Rectangular;
  CHECK(welch_line_correlation(opt, 1)[0] == Approx(0.0).margin(1e-12));
  // Measured: the errors of H1 at neighbouring bins, each scaled by its reported standard deviation, for white
  // input and white output noise.
  const SecondOrder sys = resonator(0.9, 2 * M_PI * 0.1, 1.0, 0.5, 0.2);
  const Eigen::VectorXd u = white_noise(kSamples, 12, 1.0);
  const Eigen::VectorXd y = sys.filter(u) + white_noise(kSamples, 13, 1.0);
  const WelchEstimate est = welch_h1(make_record(kDt, {{"F", u}, {"x", y}}), {"F"}, {"x"}, WelchOptions{kSegment});
  const FrfChannel& h = est.frf.channels[0];
  std::vector<cd> e;
  for (Eigen::Index k = 1; k + 1 < est.frf.f_hz.size(); ++k)
    e.push_back((h.values[k] - sys.response(est.frf.f_hz[k], kDt)) / std::sqrt(est.variance[0][k]));
  cd lag1 = 0;
  double power = 0;
  for (std::size_t k = 0; k + 1 < e.size(); ++k) lag1 += e[k] * std::conj(e[k + 1]), power += std::norm(e[k]);
  INFO("measured lag-one correlation " << lag1 / power);
  CHECK(std::abs(lag1 / power - 4.0 / 9.0) < 0.1);
}
