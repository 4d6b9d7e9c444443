// Levenberg-Marquardt on problems with known minima, under both damping updates.
#include "numerics/levenberg_marquardt.hpp"

#include <catch2/catch.hpp>

using mbgen::estimation::levenberg_marquardt;
using mbgen::estimation::LmDamping;
using mbgen::estimation::LmOptions;
using mbgen::estimation::LmResult;
using mbgen::estimation::kStalled;
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

// r = (1, exp(-x)): each Gauss-Newton step adds 1 to x, and the cost 1 + exp(-2x) falls by ever less.
bool fading(const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
  r.resize(2);
  r << 1, std::exp(-x[0]);
  if (J) {
    J->resize(2, 1);
    *J << 0, -std::exp(-x[0]);
  }
  return true;
}

// Options whose tolerances never stop a fit: only the iteration rules under test do.
LmOptions without_tolerances() {
  LmOptions o;
  o.cost_tolerance = 0;
  o.step_tolerance = 0;
  o.gradient_tolerance = 0;
  return o;
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

// fading, and r = exp(-x) alone: the cost falls at every step, towards its infimum 0 at x -> infinity.
TEST_CASE("a fit still descending at the iteration limit goes on while a window of steps gains enough",
          "[estimation][lm]") {
  const ResidualFunction steady = [](const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    r = Eigen::VectorXd::Constant(1, std::exp(-x[0]));
    if (J) *J = Eigen::MatrixXd::Constant(1, 1, -std::exp(-x[0]));
    return true;
  };
  LmOptions o = without_tolerances();
  o.max_iterations = 10;
  o.continue_window = 5;
  o.iteration_cap = 30;
  const Eigen::VectorXd x0 = Eigen::VectorXd::Zero(1);
  CHECK(levenberg_marquardt(steady, x0, o).iterations == 10);  // continue_gain 0: no continuing
  o.continue_gain = 1e-300;  // every accepted step gains something: on to the cap
  const LmResult capped = levenberg_marquardt(steady, x0, o);
  CHECK(capped.iterations == 30);
  CHECK(capped.stop_reason == "iteration limit reached");
  o.continue_gain = 1e9;  // no window gains that much
  CHECK(levenberg_marquardt(steady, x0, o).iterations == 10);
  o.continue_gain = 1e-6;
  const LmResult faded = levenberg_marquardt(fading, x0, o);
  REQUIRE(faded.iterations > 10);
  CHECK(faded.iterations < 30);
  const auto gain = [&](std::size_t end) { return 2 * std::log(faded.history[end - 5] / faded.history[end]); };
  const std::size_t last = faded.history.size() - 1;
  CHECK(gain(last) <= 1e-6);     // it stopped once the window gained too little ...
  CHECK(gain(last - 1) > 1e-6);  // ... and not before
}

// fading again: with a stall gain the fit stops, converged, at the first window of stall_window steps that gained
// less than it in n ln(cost), before it would stop otherwise.
TEST_CASE("a fit whose window of steps gains less than the stall gain stops there, converged", "[estimation][lm]") {
  LmOptions o = without_tolerances();
  o.max_iterations = 200;
  o.stall_window = 5;
  const Eigen::VectorXd x0 = Eigen::VectorXd::Zero(1);
  const LmResult unstalled = levenberg_marquardt(fading, x0, o);  // stall_gain 0: off
  CHECK(unstalled.stop_reason != kStalled);
  o.stall_gain = 1e-6;
  const LmResult stalled = levenberg_marquardt(fading, x0, o);
  CHECK(stalled.converged);
  CHECK(stalled.stop_reason == kStalled);
  REQUIRE(stalled.iterations >= 5);
  CHECK(stalled.iterations < unstalled.iterations);
  const auto gain = [&](std::size_t end) { return 2 * std::log(stalled.history[end - 5] / stalled.history[end]); };
  const std::size_t last = stalled.history.size() - 1;
  CHECK(gain(last) < 1e-6);      // it stopped once the window gained too little ...
  CHECK(gain(last - 1) >= 1e-6);  // ... and not before
}
