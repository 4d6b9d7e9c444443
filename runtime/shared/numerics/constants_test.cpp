#include "numerics/constants.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mbgen::numerics;

TEST_CASE("the constants are the doubles every former spelling gave", "[numerics]") {
  CHECK(kPi == M_PI);
  CHECK(kPi == std::acos(-1.0));
  CHECK(kTwoPi == 2 * M_PI);
  CHECK(kTwoPi == 6.283185307179586);  // the shortest spelling that reads back as the same double
}

TEST_CASE("pole frequency, damping ratio and degrees", "[numerics]") {
  const double w = 2 * M_PI * 50, zeta = 0.02;
  const std::complex<double> lambda(-zeta * w, w * std::sqrt(1 - zeta * zeta));
  CHECK(pole_frequency_hz(lambda) == Approx(50).epsilon(1e-14));
  CHECK(pole_damping_ratio(lambda) == Approx(zeta).epsilon(1e-14));
  CHECK(pole_damping_ratio(0.0) == 0.0);
  CHECK(pole_damping_ratio(-3.0) == 1.0);
  CHECK(degrees(M_PI / 2) == 90.0);
  CHECK(degrees(-M_PI) == -180.0);
}
