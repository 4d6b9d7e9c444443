#include "mbgen/dynamics/frf.hpp"
#include "mbgen/dynamics/model_modes.hpp"
#include "mbgen/sensitivity/sensitivity.hpp"
#include "mbgen_test/mdof2.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace mbgen {

TEST_CASE("local sensitivities of mdof2's modes agree with finite differences of modal_analysis", "[sensitivity]") {
  const test::Mdof2Model model;
  Eigen::VectorXd p = model.info().default_values();
  p[test::Mdof2Model::c12] = 2.0;  // some damping in the helix too
  const LocalSensitivity s = local_sensitivity(model, p);
  REQUIRE(s.modes.size() == 2);
  CHECK(s.parameters.size() == 8);
  const auto modes_at = [&](const Eigen::VectorXd& q) {
    ModelMatrices m;
    model.evaluate(q, m);
    return modal_analysis(m.M, m.C, m.K);
  };
  for (int k = 0; k < 8; ++k) {
    const double h = 1e-5 * std::abs(p[k]);
    Eigen::VectorXd up = p, down = p;
    up[k] += h;
    down[k] -= h;
    const std::vector<Mode> mu = modes_at(up), md = modes_at(down);
    for (std::size_t r = 0; r < 2; ++r) {
      INFO("parameter " << s.parameters[static_cast<std::size_t>(k)] << ", mode " << r);
      const double df = (mu[r].f_hz - md[r].f_hz) / (2 * h), dzeta = (mu[r].zeta - md[r].zeta) / (2 * h);
      CHECK(s.df_dp(static_cast<Eigen::Index>(r), k) == Approx(df).epsilon(1e-6).margin(1e-9 * s.modes[r].f_hz / p[k]));
      CHECK(s.dzeta_dp(static_cast<Eigen::Index>(r), k) == Approx(dzeta).epsilon(1e-5).margin(1e-9 / p[k]));
      CHECK(s.f_normalized(static_cast<Eigen::Index>(r), k) ==
            Approx(p[k] / s.modes[r].f_hz * s.df_dp(static_cast<Eigen::Index>(r), k)));
    }
  }
  // Scaling M, C and K together changes no eigenvalue: the normalized sensitivities of every mode sum to 0.
  for (Eigen::Index r = 0; r < 2; ++r) {
    CHECK(s.f_normalized.row(r).sum() == Approx(0).margin(1e-12));
    CHECK(s.zeta_normalized.row(r).sum() == Approx(0).margin(1e-10));
  }
  // Stiffness raises and mass lowers every frequency.
  for (Eigen::Index r = 0; r < 2; ++r) {
    CHECK(s.df_dp(r, test::Mdof2Model::k12) > 0);
    CHECK(s.df_dp(r, test::Mdof2Model::m1) < 0);
  }
}

TEST_CASE("mode visibility is each mode's share of the exact response at its frequency", "[sensitivity]") {
  const test::Mdof2Model model(/*extra_outputs=*/true);
  const Eigen::VectorXd p = model.info().default_values();
  const ModeVisibility v = mode_visibility(model, p);
  REQUIRE(v.channels == std::vector<std::string>{"d1/F1", "d2/F1", "v1/F1", "a2/F1"});
  const std::vector<Mode> modes = oscillating_modes(model, p);
  ModelMatrices m;
  model.evaluate(p, m);
  for (std::size_t r = 0; r < 2; ++r) {
    // |H| at the mode's damped frequency from the independent FRF code: peak / dominance must give it back.
    const FrfResult h = frf(m, {modes[r].eigenvalue.imag() / (2 * M_PI)});
    for (Eigen::Index c = 0; c < 4; ++c)
      CHECK(v.peak(static_cast<Eigen::Index>(r), c) / v.dominance(static_cast<Eigen::Index>(r), c) ==
            Approx(std::abs(h.H[0](c, 0))).epsilon(1e-9));
    CHECK(v.dominance.row(static_cast<Eigen::Index>(r)).maxCoeff() > 0.5);  // lightly damped: each mode dominates
  }
}

}  // namespace mbgen
