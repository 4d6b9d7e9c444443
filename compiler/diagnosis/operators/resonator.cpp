// resonator:B -- an unmodelled local mode (a flexible part, a loose fixture) near where B is excited or
// measured: a small mass on a spring-damper attached to B at that point, moving along the measured direction.
// Only offered with an unexplained peak to explain: its start frequency is that peak.
#include <cmath>

#include "diagnosis/expr_build.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

namespace {

Extension extend(const OperatorInput& in, const ir::Body& b, const SignalPoint& at, int axis) {
  Draft d(in, "resonator", b.name);
  const double mass = in.values.of(b.mass);
  const double mr = 0.02 * mass;
  const double omega = kTwoPi * in.ctx.peak_hz.front();
  const double kr = mr * omega * omega;
  const std::string mr_b = d.add_parameter("mr_" + b.name, mr, "kg", 1e-4 * mass, mass, "mass of the resonator on " + b.name);
  const std::string kr_b = d.add_parameter("kr_" + b.name, kr, "N/m", 0.0, std::nullopt, "stiffness of the resonator on " + b.name);
  const std::string cr_b = d.add_parameter("cr_" + b.name, light_damping(kr, mr), "N s/m", 0.0, std::nullopt,
                                           "damping of the resonator on " + b.name);
  d.add_resonating_body(add_body_on_axial_spring(d, "res_" + b.name, mr_b, at.at->point, axis, b.name, "_spring", kr_b, cr_b));

  char hz[32];
  std::snprintf(hz, sizeof hz, "%.4g", in.ctx.peak_hz.front());
  return d.finish("a local mode near " + std::string(hz) + " Hz: a mass " + mr_b + " on a spring-damper (" + kr_b + ", " +
                  cr_b + ") attached to " + b.name + " at the point of " + at.signal + ", moving along " +
                  std::string(1, "xyz"[axis]));
}

}  // namespace

std::vector<Extension> resonator(const OperatorInput& in) {
  std::vector<Extension> out;
  if (in.ctx.peak_hz.empty()) return out;
  for (const ir::Body& b : in.model.bodies) {
    const std::optional<SignalPoint> at = signal_point(in.model, b.name);
    if (!at) continue;
    // A body's coordinates are along the global axes: an oblique measured direction has no single one.
    const std::optional<int> axis = axis_of(*at->direction, in.values);
    if (!axis) continue;
    out.push_back(extend(in, b, *at, *axis));
  }
  return out;
}

}  // namespace mbgen::diagnosis
