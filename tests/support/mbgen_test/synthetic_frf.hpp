// Test helper: FRFs of a hand-assembled modal model with known modes, written out directly as the receptance of
// a proportionally damped structure,
//   H_oi(w) = sum_r phi_o(r) phi_i(r) / (m_r (w_r^2 - w^2 + 2 i zeta_r w_r w)),
// times (i w)^power for mobility or accelerance, plus seeded complex Gaussian noise. Independent of the code
// under test (no pole-residue form, no LSCF/LSFD code). Header-only; for tests and benchmarks.
#pragma once

#include "mbgen/data/frf_data.hpp"
#include "numerics/constants.hpp"

#include <Eigen/Core>

#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <vector>

namespace mbgen::test {

struct TrueMode {
  double f_hz = 0, zeta = 0;
  std::vector<double> shape;  // at every point (outputs and inputs index into it)
  double modal_mass = 1;
};

struct SyntheticFrfSpec {
  std::vector<TrueMode> modes;
  std::vector<int> output_points, input_points;  // channels: every output x input
  double f_lo = 1, f_hi = 400;
  int lines = 400;
  int power = 0;     // 0 receptance, 1 mobility, 2 accelerance
  double noise = 0;  // sigma of the complex noise per line, relative to the channel's RMS
  unsigned seed = 1;
};

// The exact receptance residue of mode r at channel (o, i): phi_o phi_i / (2 i w_d m_r).
inline std::complex<double> true_receptance_residue(const TrueMode& m, int o, int i) {
  const double w = numerics::kTwoPi * m.f_hz, wd = w * std::sqrt(1 - m.zeta * m.zeta);
  return m.shape[static_cast<std::size_t>(o)] * m.shape[static_cast<std::size_t>(i)] /
         (std::complex<double>(0, 2 * wd) * m.modal_mass);
}

inline FrfData synthetic_frf(const SyntheticFrfSpec& spec, const std::string& file = "synthetic") {
  FrfData data;
  data.file = file;
  data.f_hz = Eigen::VectorXd::LinSpaced(spec.lines, spec.f_lo, spec.f_hi);
  std::mt19937 rng(spec.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int o : spec.output_points)
    for (int i : spec.input_points) {
      FrfChannel ch;
      ch.output = "y" + std::to_string(o);
      ch.input = "u" + std::to_string(i);
      ch.values.resize(spec.lines);
      for (int k = 0; k < spec.lines; ++k) {
        const double w = numerics::kTwoPi * data.f_hz[k];
        std::complex<double> h = 0;
        for (const TrueMode& m : spec.modes) {
          const double wr = numerics::kTwoPi * m.f_hz;
          h += m.shape[static_cast<std::size_t>(o)] * m.shape[static_cast<std::size_t>(i)] /
               (m.modal_mass * std::complex<double>(wr * wr - w * w, 2 * m.zeta * wr * w));
        }
        ch.values[k] = h * std::pow(std::complex<double>(0, w), spec.power);
      }
      if (spec.noise > 0) {
        const double sigma = spec.noise * ch.values.norm() / std::sqrt(static_cast<double>(spec.lines));
        for (int k = 0; k < spec.lines; ++k)
          ch.values[k] += sigma / std::sqrt(2.0) * std::complex<double>(normal(rng), normal(rng));
      }
      data.channels.push_back(std::move(ch));
    }
  return data;
}

}  // namespace mbgen::test
