// Uses the generated spindle model through the runtime: its modes and the FRF at the nose around the first two
// resonances.
#include <cstdio>

#include <mbgen/dynamics/frf.hpp>
#include <mbgen/dynamics/model_modes.hpp>

#include "spindle_model.hpp"

int main() {
  const auto model = mbgen_models::spindle::make_model();
  const Eigen::VectorXd p = model->info().default_values();
  mbgen::ModelMatrices m;
  model->evaluate(p, m);
  for (const mbgen::Mode& mode : mbgen::modal_analysis(m.M, m.C, m.K)) std::printf("mode %.1f Hz\n", mode.f_hz);
  const mbgen::FrfResult h = mbgen::frf(*model, p, {200.0, 231.1, 286.3, 400.0});
  for (std::size_t k = 0; k < h.freqs_hz.size(); ++k)
    std::printf("|xs_front/Fx| at %.1f Hz: %.3e m/N\n", h.freqs_hz[k], std::abs(h.H[k](0, 0)));
  return 0;
}
