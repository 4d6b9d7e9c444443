#include "diagnosis/engine/new_body_modes.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"

namespace mbgen::diagnosis {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// A 1.3 kg machine on a spring (its own mode near 160 Hz) to a wall that is a body of mass mw held to a fixed
// ground by kw and cw: what compliant_ground makes of a ground.
const char* const kMachineOnWall =
    "model machine\n"
    "param m1 = 1.3 \"kg\" estimate in [0, 100]\n"
    "param k1 = 1.3e6 \"N/m\" estimate in [0, 1e9]\n"
    "param c1 = 10 \"N s/m\" estimate in [0, 1e4]\n"
    "param mw = 5 \"kg\" estimate in [0, 1e4]\n"
    "param kw = 1e7 \"N/m\" estimate in [0, 1e12]\n"
    "param cw = 100 \"N s/m\" estimate in [0, 1e9]\n"
    "ground fixed\n"
    "body wall {\n  mass mw\n  dof x\n}\n"
    "body mass1 {\n  mass m1\n  dof x\n}\n"
    "spring support {\n  from fixed\n  to wall\n  along x\n  stiffness kw\n  damping cw\n}\n"
    "spring beam {\n  from wall\n  to mass1\n  along x\n  stiffness k1\n  damping c1\n}\n"
    "input F1 force on mass1 along x\n"
    "output d1 displacement of mass1 along x\n";

// The wall's values for its own frequency f (Hz) and damping ratio zeta, the machine's as declared.
Eigen::VectorXd wall(double mw, double f, double zeta) {
  const double kw = mw * std::pow(kTwoPi * f, 2);
  Eigen::VectorXd p(6);
  p << 1.3, 1.3e6, 10, mw, kw, 2 * zeta * std::sqrt(kw * mw);
  return p;
}

std::vector<ChannelResidual> measured(double f_lo, double f_hi) {
  ChannelResidual c;
  c.channel = "d1/F1";
  c.f_hz = {f_lo, f_hi};
  return {c};
}

TEST_CASE("new body modes: a light, lightly damped wall in the band is a resonance the data show") {
  const auto model = evaluator::make_evaluator(frontend::parse_string(kMachineOnWall, "test.mdl"));
  const NewBodyMode m = best_seen_new_body_mode(*model, wall(5, 250, 0.02), {"wall"}, measured(10, 1000));
  CHECK(m.oscillating);
  CHECK(m.channel == "d1/F1");
  CHECK(m.f_hz > 200);  // the wall's mode, not the machine's (below 160 Hz with the wall's compliance)
  CHECK(m.share > 0.5);
}

TEST_CASE("new body modes: a heavy wall damped at 40 % of critical carries almost nothing of the response") {
  const auto model = evaluator::make_evaluator(frontend::parse_string(kMachineOnWall, "test.mdl"));
  const NewBodyMode m = best_seen_new_body_mode(*model, wall(400, 146, 0.4), {"wall"}, measured(10, 1000));
  CHECK(m.oscillating);
  CHECK(m.channel == "d1/F1");
  CHECK(m.zeta == Approx(0.4).epsilon(0.05));
  CHECK(m.share < 0.05);
}

TEST_CASE("new body modes: an overdamped wall has no resonance, and a mode outside the band no channel") {
  const auto model = evaluator::make_evaluator(frontend::parse_string(kMachineOnWall, "test.mdl"));
  CHECK_FALSE(best_seen_new_body_mode(*model, wall(400, 146, 1.5), {"wall"}, measured(10, 1000)).oscillating);
  const NewBodyMode above = best_seen_new_body_mode(*model, wall(5, 3000, 0.02), {"wall"}, measured(10, 1000));
  CHECK(above.oscillating);
  CHECK(above.channel.empty());
  // A channel the model does not have is not looked at.
  std::vector<ChannelResidual> other = measured(10, 1000);
  other[0].channel = "d9/F1";
  CHECK(best_seen_new_body_mode(*model, wall(5, 250, 0.02), {"wall"}, other).channel.empty());
}

TEST_CASE("new body modes: the machine's own mode is not the wall's") {
  // The wall stiff and light: its mode far above, the machine's at ~160 Hz dominates the channel. Only the wall's
  // mode (one coordinate: one mode) is judged, and it lies outside the band.
  const auto model = evaluator::make_evaluator(frontend::parse_string(kMachineOnWall, "test.mdl"));
  const NewBodyMode m = best_seen_new_body_mode(*model, wall(5, 5000, 0.02), {"wall"}, measured(10, 1000));
  CHECK(m.f_hz > 4000);
  CHECK(m.channel.empty());
}

}  // namespace
}  // namespace mbgen::diagnosis
