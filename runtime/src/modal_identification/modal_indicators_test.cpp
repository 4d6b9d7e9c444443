#include "mbgen/modal_identification/modal_identification.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace mbgen {

TEST_CASE("MPC and MPD of real, rotated and complex shapes", "[modal][indicators]") {
  const double deg = std::acos(-1.0) / 180;
  Eigen::VectorXcd real(4);
  real << 1.0, -0.5, 0.25, 2.0;
  CHECK(modal_phase_collinearity(real) == Approx(1).margin(1e-14));
  CHECK(mean_phase_deviation_deg(real) == Approx(0).margin(1e-6));
  // A complex factor (the residue's arbitrary phase) changes neither.
  const Eigen::VectorXcd rotated = real * std::polar(3.0, 0.7);
  CHECK(modal_phase_collinearity(rotated) == Approx(1).margin(1e-14));
  CHECK(mean_phase_deviation_deg(rotated) == Approx(0).margin(1e-6));
  // Two equal components 10 degrees apart: each lies 5 degrees off the best line.
  Eigen::VectorXcd spread(2);
  spread << 1.0, std::polar(1.0, 10 * deg);
  CHECK(mean_phase_deviation_deg(spread) == Approx(5).epsilon(1e-9));
  // MPC = ((l1 - l2) / (l1 + l2))^2 with l the eigenvalues of [Re Im]^T [Re Im], here 1 +- cos(10 deg).
  CHECK(modal_phase_collinearity(spread) == Approx(std::pow(std::cos(10 * deg), 2)).epsilon(1e-12));
  // Components in quadrature of equal size: no line fits better than another.
  Eigen::VectorXcd quadrature(2);
  quadrature << 1.0, std::complex<double>(0, 1);
  CHECK(modal_phase_collinearity(quadrature) == Approx(0).margin(1e-14));
  Eigen::VectorXcd single(1);
  single << std::complex<double>(0.3, -2);
  CHECK(modal_phase_collinearity(single) == Approx(1));
  CHECK(modal_phase_collinearity(Eigen::VectorXcd::Zero(3)) == 0);
}

}  // namespace mbgen
