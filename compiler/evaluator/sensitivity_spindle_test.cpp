// Feature maps of the spindle (examples/spindle/spindle.mdl): the front bearing's x stiffness standing for its
// preload (thesis Sec. 5.4.4, Fig. 5.34). Beside the evaluator because it needs the model from the .mdl, as
// fit_spindle_test does.
#include "mbgen_test/files.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"

#include "mbgen/sensitivity/sensitivity.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mbgen;

TEST_CASE("sensitivity: the spindle's feature map over the front bearing's stiffness", "[sensitivity][spindle]") {
  const auto model = evaluator::make_evaluator(frontend::parse_file(mbgen::test::example_model_path("spindle")));
  const Eigen::VectorXd p = model->info().default_values();
  const int k_fx = model->info().parameter_index("k_fx");
  REQUIRE(k_fx >= 0);
  const FeatureMap map = feature_map(*model, p, k_fx, 0.5 * p[k_fx], 4 * p[k_fx], 15);
  REQUIRE(map.f_hz.cols() == 11);
  REQUIRE(map.f_hz.allFinite());
  int moved = 0;
  for (Eigen::Index t = 0; t < map.f_hz.cols(); ++t) {
    const double start = map.f_hz(0, t), end = map.f_hz(14, t);
    INFO("trace from " << start << " Hz to " << end << " Hz, zeta " << map.zeta(0, t) << " -> " << map.zeta(14, t));
    // A stiffer bearing raises every frequency or leaves it (Rayleigh: dK is positive semi-definite)...
    for (Eigen::Index k = 1; k < 15; ++k) CHECK(map.f_hz(k, t) >= map.f_hz(k - 1, t) * (1 - 1e-9));
    // ... the modes of the y direction and the axial one do not see it at all (the blocks are uncoupled)...
    if (end < start * (1 + 1e-9)) {
      CHECK(map.zeta(14, t) == Approx(map.zeta(0, t)).epsilon(1e-9));
      continue;
    }
    // ... and the modes it moves by more than 5 % lose damping ratio: the bearing's damper stays as it is while
    // the stiffness it works against grows (zeta ~ c / (2 sqrt(k m))). The traces move right and down.
    if (end > 1.05 * start) {
      ++moved;
      CHECK(map.zeta(14, t) < map.zeta(0, t));
    }
  }
  CHECK(moved >= 4);

  // The local sensitivities say the same: positive df/dk_fx for those modes, none for the others.
  const LocalSensitivity local = local_sensitivity(*model, p);
  for (Eigen::Index r = 0; r < local.df_dp.rows(); ++r)
    CHECK(local.df_dp(r, k_fx) >= -1e-12 * local.modes[static_cast<std::size_t>(r)].f_hz);
}
