// MATLAB's compare fit percentage (mbgen/estimation/validation_fit.hpp) on values computed by hand.
#include "mbgen/estimation/validation_fit.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mbgen;

TEST_CASE("the fit percentage of a record's output and of an FRF", "[validation]") {
  using C = std::complex<double>;
  // A record: y = 1 2 3, the model 1 2 4: ||y - yhat|| = 1, ||y - mean y|| = sqrt(2).
  Eigen::VectorXcd y(3), yhat(3);
  y << 1, 2, 3;
  yhat << 1, 2, 4;
  CHECK(compare_fit_percent(y, yhat, true) == Approx(100 * (1 - 1 / std::sqrt(2.0))));
  CHECK(compare_fit_percent(y, y, true) == 100);
  // Worse than the mean: negative.
  CHECK(compare_fit_percent(y, -y, true) < 0);
  // An FRF: H = 1, j, the model 1, 0: ||H - Hhat|| = 1, ||H|| = sqrt(2) (no mean removed).
  Eigen::VectorXcd h(2), hhat(2);
  h << C(1, 0), C(0, 1);
  hhat << C(1, 0), C(0, 0);
  CHECK(compare_fit_percent(h, hhat, false) == Approx(100 * (1 - 1 / std::sqrt(2.0))));
  // Nothing to compare against: NaN, written as null.
  CHECK(std::isnan(compare_fit_percent(Eigen::VectorXcd::Constant(4, C(2, 0)), Eigen::VectorXcd::Zero(4), true)));
}
