#include "mbgen/sensitivity/sensitivity.hpp"
#include "mbgen_test/mdof2.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace mbgen {

TEST_CASE("feature maps of mdof2: stiffness raises, mass lowers, damping damps", "[sensitivity][feature_map]") {
  const test::Mdof2Model model;
  const Eigen::VectorXd p = model.info().default_values();
  using P = test::Mdof2Model::Param;
  // k11 from a tenth to ten times nominal: the modes veer (mode 1 is mass 1's at first, mass 2's at the end), the
  // traces follow the shapes, and by Rayleigh's quotient (dK positive semi-definite) no frequency falls.
  const FeatureMap k = feature_map(model, p, P::k11, 0.1 * p[P::k11], 10 * p[P::k11], 60);
  CHECK(k.parameter == "k11");
  REQUIRE(k.f_hz.cols() == 2);
  CHECK(k.f_hz.allFinite());
  for (Eigen::Index t = 0; t < 2; ++t)
    for (Eigen::Index i = 1; i < 60; ++i) CHECK(k.f_hz(i, t) >= k.f_hz(i - 1, t) * (1 - 1e-12));
  // The sweep's ends against a direct modal analysis (traces are in the start's frequency order).
  Eigen::VectorXd q = p;
  q[P::k11] = 10 * p[P::k11];
  const std::vector<Mode> end = oscillating_modes(model, q);
  CHECK(std::min(k.f_hz(59, 0), k.f_hz(59, 1)) == Approx(end[0].f_hz));
  CHECK(std::max(k.f_hz(59, 0), k.f_hz(59, 1)) == Approx(end[1].f_hz));

  const FeatureMap m = feature_map(model, p, P::m2, 0.5 * p[P::m2], 2 * p[P::m2], 20);
  for (Eigen::Index t = 0; t < 2; ++t)
    for (Eigen::Index i = 1; i < 20; ++i) CHECK(m.f_hz(i, t) <= m.f_hz(i - 1, t) * (1 + 1e-12));

  // More damping in beam 1: both modes' damping ratios grow (dC positive semi-definite), frequencies barely move.
  const FeatureMap c = feature_map(model, p, P::c11, 0.5 * p[P::c11], 4 * p[P::c11], 20);
  for (Eigen::Index t = 0; t < 2; ++t) {
    for (Eigen::Index i = 1; i < 20; ++i) CHECK(c.zeta(i, t) > c.zeta(i - 1, t));
    CHECK(std::abs(c.f_hz(19, t) / c.f_hz(0, t) - 1) < 1e-3);
  }
  CHECK_THROWS(feature_map(model, p, 99, 0, 1, 10));
  CHECK_THROWS(feature_map(model, p, P::m1, 1, 2, 1));
}

}  // namespace mbgen
