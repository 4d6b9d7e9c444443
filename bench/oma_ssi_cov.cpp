// oma_ssi_cov: output-only modal analysis (SSI-cov and FDD) on 8 channels x 10^6 samples: eight modes, each the
// response of a discrete resonator (x_k = 2 r cos(w dt) x_(k-1) - r^2 x_(k-2) + e_k, its own white noise, so the
// modes are independent), seen at the eight channels through sine shapes; 1 % white noise on each channel. Prints
// the wall time of the correlations (FFT), of SSI-cov in all and of FDD in all, and the modes found against the
// resonators' poles. Issue 34's target: SSI-cov under 30 s on 2 cores. See README.md.
#include "mbgen/modal_identification/output_only_modal.hpp"
#include "seconds_since.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

int main(int argc, char** argv) {
  const Eigen::Index samples = argc > 1 ? std::atol(argv[1]) : 1000000;
  const int channels = 8, modes = 8;
  const double dt = 1e-3, zeta = 0.01, pi = std::acos(-1.0);
  std::mt19937 rng(34);
  std::normal_distribution<double> normal;
  mbgen::ResponseData data;
  data.dt = dt;
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(samples, channels);
  std::vector<double> f_true(modes);
  for (int m = 0; m < modes; ++m) {
    const double f = 20 + 45 * m, w = 2 * pi * f, r = std::exp(-zeta * w * dt);
    f_true[static_cast<std::size_t>(m)] = std::hypot(w, zeta * w) / (2 * pi);  // |ln(r e^(i w dt))| / dt
    double a = 0, b = 0;
    for (Eigen::Index k = 0; k < samples; ++k) {
      const double x = 2 * r * std::cos(w * dt) * a - r * r * b + normal(rng);
      b = a;
      a = x;
      for (int c = 0; c < channels; ++c) y(k, c) += std::sin((c + 1) * (m + 1) * pi / 9) * x;
    }
  }
  for (int c = 0; c < channels; ++c) {
    const double rms = std::sqrt(y.col(c).squaredNorm() / static_cast<double>(samples));
    for (Eigen::Index k = 0; k < samples; ++k) y(k, c) += 0.01 * rms * normal(rng);
    data.channels.push_back("c" + std::to_string(c + 1));
    data.references.push_back(c);
  }
  data.records = {y};
  std::printf("%d channels x %ld samples, %d modes (zeta %.2f)\n", channels, static_cast<long>(samples), modes, zeta);
  auto t0 = std::chrono::steady_clock::now();
  mbgen::output_correlations(data, 64);
  std::printf("correlations, 64 lags (FFT): %.2f s\n", mbgen::bench::seconds_since(t0));
  for (const mbgen::OutputOnlyMethod method : {mbgen::OutputOnlyMethod::SsiCov, mbgen::OutputOnlyMethod::Fdd}) {
    mbgen::OutputOnlyOptions options;
    options.method = method;
    t0 = std::chrono::steady_clock::now();
    const mbgen::OutputOnlyIdentification r = mbgen::identify_output_only(data, options);
    std::printf("%s: %.2f s, %zu modes\n", mbgen::output_only_method_name(method), mbgen::bench::seconds_since(t0),
                r.modes.size());
    for (const mbgen::OperationalMode& m : r.modes) {
      double nearest = f_true.front();
      for (double f : f_true)
        if (std::abs(f - m.f_hz) < std::abs(nearest - m.f_hz)) nearest = f;
      std::printf("  %9.4f Hz (%+.3f %%)  zeta %.5f (%+.1f %%)\n", m.f_hz, 100 * (m.f_hz / nearest - 1), m.zeta,
                  100 * (m.zeta / zeta - 1));
    }
  }
  return 0;
}
