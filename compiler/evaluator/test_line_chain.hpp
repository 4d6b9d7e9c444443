// An identifiable chain for fits at machine scale (issue 14): N bodies on one axis, body i held to body i-1 (the
// first to the ground) by a spring-damper; 3N parameters (m_i, k_i, c_i), one force on the free end (body N, the
// "tool tip"), accelerometers on every `every`-th body counted from the tip. Where the six-coordinate chain of
// compiler/symbolic/test_chain_model.hpp measures 2 of 6N coordinates (most of its parameters in flat valleys),
// here the data see the whole chain: a fixed-free chain is already determined by its driving-point FRF (the
// inverse eigenvalue problem of a Jacobi matrix), and the other sensors make that well conditioned.
//
// Two independent routes to the same FRFs, for the tests and bench/fit_line_chain:
//   - model_text(): the .mdl text, which the code under test parses, derives and evaluates;
//   - accelerance(): M, C, K assembled here by hand (tridiagonal) and solved by the Thomas algorithm, sharing
//     nothing with the compiler or the runtime (draw() puts its values with noise into an FrfData).
#pragma once

#include "mbgen/data/frf_data.hpp"
#include "mbgen/model.hpp"
#include "numerics/constants.hpp"

#include <cmath>
#include <complex>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace mbgen::test::line_chain {

// Nominal values of body i (1-based; deterministic and varied, no two neighbours alike): 80..260 kg,
// 40..88 MN/m, and dampers of 4..12 kN s/m (modal damping from about 0.2 % for the lowest mode to about 10 % for the highest).
inline double nominal_mass(int i) { return 80.0 + 8.0 * ((i * 37) % 23); }
inline double nominal_stiffness(int i) { return (40.0 + 3.0 * ((i * 11) % 17)) * 1e6; }
inline double nominal_damping(int i) { return 4000.0 + 500.0 * ((i * 13) % 17); }

// The sensed bodies, tip first: N, N - every, ..., and the first (next to the ground, where the chain moves least).
inline std::vector<int> sensor_bodies(int bodies, int every) {
  std::vector<int> out;
  for (int i = bodies; i >= 1; i -= every) out.push_back(i);
  if (out.back() != 1) out.push_back(1);
  return out;
}

inline std::string output_name(int body) { return "a" + std::to_string(body); }

// Parameters in model order m1 k1 c1 m2 k2 c2 ...; every one `estimate`, bounded below by 0 (a log transform).
inline std::string model_text(int bodies, int every) {
  auto num = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return std::string(buf);
  };
  std::string t = "# A chain of " + std::to_string(bodies) + " bodies along x (test_line_chain.hpp).\nmodel line_chain" +
                  std::to_string(bodies) + "\n\nground base\n";
  for (int i = 1; i <= bodies; ++i) {
    const std::string n = std::to_string(i);
    auto param = [&](const char* name, double v, const char* unit) {
      t += std::string("param ") + name + n + " = " + num(v) + " \"" + unit + "\" estimate in [0, inf]\n";
    };
    param("m", nominal_mass(i), "kg");
    param("k", nominal_stiffness(i), "N/m");
    param("c", nominal_damping(i), "N s/m");
  }
  for (int i = 1; i <= bodies; ++i) {
    const std::string n = std::to_string(i);
    t += "body b" + n + " {\n  mass m" + n + "\n  dof x\n}\n";
    t += "spring s" + n + " {\n  from " + (i == 1 ? std::string("base") : "b" + std::to_string(i - 1)) + "\n  to b" + n +
         "\n  along x\n  stiffness k" + n + "\n  damping c" + n + "\n}\n";
  }
  t += "input F force on b" + std::to_string(bodies) + " along x\n";
  for (int b : sensor_bodies(bodies, every)) t += "output " + output_name(b) + " acceleration of b" + std::to_string(b) + " along x\n";
  return t;
}

// Accelerance -w^2 X_b / F of every sensed body (sensor_bodies order) at f_hz, for masses m, stiffnesses k and
// dampers c (0-based: body i + 1). P(jw) = K - w^2 M + jw C is tridiagonal: spring j joins bodies j - 1 and j.
inline std::vector<std::complex<double>> accelerance(const std::vector<double>& m, const std::vector<double>& k,
                                                     const std::vector<double>& c, const std::vector<int>& sensors,
                                                     double f_hz) {
  using cd = std::complex<double>;
  const std::size_t n = m.size();
  const double w = numerics::kTwoPi * f_hz;
  auto z = [&](std::size_t j) { return cd(k[j], w * c[j]); };  // spring-damper j's dynamic stiffness
  std::vector<cd> diag(n), off(n);                              // off[i]: entry (i, i+1) = (i+1, i)
  for (std::size_t i = 0; i < n; ++i) {
    diag[i] = z(i) - w * w * m[i] + (i + 1 < n ? z(i + 1) : cd(0));
    if (i + 1 < n) off[i] = -z(i + 1);
  }
  // Thomas algorithm for P x = e_{n-1} (the force on the last body).
  std::vector<cd> cp(n), dp(n);
  cp[0] = off[0] / diag[0];
  dp[0] = cd(n == 1 ? 1 : 0) / diag[0];
  for (std::size_t i = 1; i < n; ++i) {
    const cd denom = diag[i] - off[i - 1] * cp[i - 1];
    cp[i] = i + 1 < n ? off[i] / denom : cd(0);
    dp[i] = (cd(i + 1 == n ? 1 : 0) - off[i - 1] * dp[i - 1]) / denom;
  }
  std::vector<cd> x(n);
  x[n - 1] = dp[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) x[i] = dp[i] - cp[i] * x[i + 1];
  std::vector<cd> out;
  for (int b : sensors) out.push_back(-w * w * x[static_cast<std::size_t>(b - 1)]);
  return out;
}

// One synthetic measurement: the truth (every parameter's nominal value times a factor uniform in
// [1 - spread, 1 + spread] from `seed`) and its accelerances at kLines log-spaced lines over 2..400 Hz with kNoise
// complex noise proportional to |H| (the same seeded stream), carrying the matching coherence: FrfWeighting's H1
// variance (1 - g2) / g2 |H|^2 is then the noise's, so the fit's std are meant to hold.
constexpr int kLines = 400;
constexpr double kNoise = 0.01;

struct Draw {
  Eigen::VectorXd truth;  // in the model's parameter order
  FrfData data;
};

inline Draw draw(const ModelInfo& info, int bodies, int every, unsigned seed, double spread) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> factor(1 - spread, 1 + spread);
  std::vector<double> m(static_cast<std::size_t>(bodies)), k(m.size()), c(m.size());
  Draw out;
  out.truth = info.default_values();
  for (int i = 0; i < bodies; ++i) {
    const std::string n = std::to_string(i + 1);
    m[i] = nominal_mass(i + 1) * factor(rng);
    k[i] = nominal_stiffness(i + 1) * factor(rng);
    c[i] = nominal_damping(i + 1) * factor(rng);
    out.truth[info.parameter_index("m" + n)] = m[i];
    out.truth[info.parameter_index("k" + n)] = k[i];
    out.truth[info.parameter_index("c" + n)] = c[i];
  }
  const std::vector<int> sensors = sensor_bodies(bodies, every);
  out.data.file = "line chain " + std::to_string(bodies) + " seed " + std::to_string(seed) + " (synthetic)";
  out.data.f_hz.resize(kLines);
  for (int j = 0; j < kLines; ++j) out.data.f_hz[j] = 2.0 * std::pow(200.0, double(j) / (kLines - 1));
  for (int b : sensors) {
    FrfChannel ch;
    ch.output = output_name(b);
    ch.input = "F";
    ch.values.resize(kLines);
    ch.coherence = Eigen::VectorXd::Constant(kLines, 1 / (1 + kNoise * kNoise));  // (1 - g2) / g2 = kNoise^2
    out.data.channels.push_back(ch);
  }
  std::normal_distribution<double> noise(0.0, kNoise / std::sqrt(2.0));
  for (int j = 0; j < kLines; ++j) {
    const auto h = accelerance(m, k, c, sensors, out.data.f_hz[j]);
    for (std::size_t s = 0; s < sensors.size(); ++s)
      out.data.channels[s].values[j] = h[s] * std::complex<double>(1 + noise(rng), noise(rng));
  }
  return out;
}

}  // namespace mbgen::test::line_chain
