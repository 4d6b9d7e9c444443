// Levenberg-Marquardt on problems with known minima, under both damping updates.
#include "levenberg_marquardt.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using mbgen::estimation::levenberg_marquardt;
using mbgen::estimation::LmDamping;
using mbgen::estimation::LmOptions;
using mbgen::estimation::LmResult;
using mbgen::estimation::ResidualFunction;

namespace {

// Rosenbrock's valley as least squares: r = (10 (x1 - x0^2), 1 - x0), minimum 0 at (1, 1). `evaluations` counts
// the calls (trials and Jacobians).
ResidualFunction rosenbrock(int& evaluations) {
  return [&evaluations](const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    ++evaluations;
    r.resize(2);
    r << 10 * (x[1] - x[0] * x[0]), 1 - x[0];
    if (J) {
      J->resize(2, 2);
      *J << -20 * x[0], 10, -1, 0;
    }
    return true;
  };
}

LmResult solve(LmDamping damping, const Eigen::VectorXd& x0, int& evaluations) {
  LmOptions o;
  o.damping = damping;
  o.max_iterations = 500;
  return levenberg_marquardt(rosenbrock(evaluations), x0, o);
}

}  // namespace

TEST_CASE("both damping updates reach the minimum of Rosenbrock's valley", "[estimation][lm]") {
  for (const LmDamping damping : {LmDamping::Classic, LmDamping::Nielsen}) {
    for (const Eigen::Vector2d& x0 : {Eigen::Vector2d(-1.2, 1.0), Eigen::Vector2d(2.5, -1.0), Eigen::Vector2d(0, 3)}) {
      INFO("damping " << static_cast<int>(damping) << ", start " << x0.transpose());
      int evaluations = 0;
      const LmResult r = solve(damping, x0, evaluations);
      CHECK(r.converged);
      CHECK(r.x[0] == Approx(1).epsilon(1e-7));
      CHECK(r.x[1] == Approx(1).epsilon(1e-7));
      CHECK(r.cost < 1e-14);
      // The cost never rises: only decreasing steps are taken.
      for (std::size_t i = 1; i < r.history.size(); ++i) CHECK(r.history[i] < r.history[i - 1]);
    }
  }
}

TEST_CASE("the damping update decides the path: Nielsen's differs from the classic", "[estimation][lm]") {
  int classic_evaluations = 0, nielsen_evaluations = 0;
  const LmResult classic = solve(LmDamping::Classic, Eigen::Vector2d(-1.2, 1.0), classic_evaluations);
  const LmResult nielsen = solve(LmDamping::Nielsen, Eigen::Vector2d(-1.2, 1.0), nielsen_evaluations);
  REQUIRE(classic.history.size() > 2);
  REQUIRE(nielsen.history.size() > 2);
  // Both start at lambda = 1e-3; a rejected trial raises it by 10 or by 2, an accepted step lowers it by 3 or by the
  // gain ratio's factor: the paths part at once.
  CHECK(classic.history[0] == nielsen.history[0]);
  CHECK(classic.history[1] != nielsen.history[1]);
}

TEST_CASE("a point where the residuals cannot be evaluated is a failed trial", "[estimation][lm]") {
  for (const LmDamping damping : {LmDamping::Classic, LmDamping::Nielsen}) {
    int evaluations = 0;
    const ResidualFunction inner = rosenbrock(evaluations);
    // Not admissible beyond x0 = 1.05: the minimum at 1 stays reachable.
    const ResidualFunction bounded = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
      return x[0] <= 1.05 && inner(x, r, J);
    };
    LmOptions o;
    o.damping = damping;
    o.max_iterations = 500;
    const LmResult r = levenberg_marquardt(bounded, Eigen::Vector2d(-1.2, 1.0), o);
    CHECK(r.converged);
    CHECK(r.x[0] == Approx(1).epsilon(1e-6));
    CHECK(r.x[0] <= 1.05);
  }
}

// r = (1, 1/x): the cost 1 + 1/x^2 falls towards its infimum at x -> infinity by ever smaller amounts (each
// Gauss-Newton step doubles x), the way a fit crawls along a poorly determined direction.
TEST_CASE("a crawl stops once a window of steps gains less than the stall gain in n ln(cost)", "[estimation][lm]") {
  const ResidualFunction crawl = [](const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    if (!(x[0] > 0)) return false;
    r.resize(2);
    r << 1, 1 / x[0];
    if (J) {
      J->resize(2, 1);
      *J << 0, -1 / (x[0] * x[0]);
    }
    return true;
  };
  LmOptions o;
  o.cost_tolerance = 0;
  o.step_tolerance = 0;
  o.gradient_tolerance = 0;
  o.max_iterations = 60;
  const LmResult plain = levenberg_marquardt(crawl, Eigen::VectorXd::Constant(1, 1.0), o);
  CHECK(plain.stop_reason != "stalled: the last steps lowered the cost by less than the stall gain");
  o.stall_window = 5;
  o.stall_gain = 0.05;
  const LmResult stalled = levenberg_marquardt(crawl, Eigen::VectorXd::Constant(1, 1.0), o);
  CHECK(stalled.stop_reason == "stalled: the last steps lowered the cost by less than the stall gain");
  CHECK(stalled.converged);
  REQUIRE(stalled.iterations > 5);
  CHECK(stalled.iterations < plain.iterations);
  // Where it stopped, the last five steps gained under the stall gain and the five before more.
  const auto& h = stalled.history;
  const std::size_t last = h.size() - 1;
  CHECK(2 * std::log(h[last - 5] / h[last]) < 0.05);
  CHECK(2 * std::log(h[last - 6] / h[last - 1]) >= 0.05);
}
