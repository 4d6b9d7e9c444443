// Levenberg-Marquardt on problems with known minima, under both damping updates.
#include "levenberg_marquardt.hpp"

#include <catch2/catch.hpp>

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
