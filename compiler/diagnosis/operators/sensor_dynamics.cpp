// sensor_dynamics:O -- output O is not the structure's motion but what its sensor makes of it. The sensor is
// modelled as what it physically is: a small mass (an accelerometer on its mounting) on a spring-damper at the
// measured point, moving along the measured direction, and O measures that mass. Seen from the structure's
// motion y, the sensor reads T(s) y with T = (c s + k)/(m s^2 + c s + k): a second-order low-pass with its
// resonance at the mounting frequency. A pure delay is not a mechanical element and is not represented.
//
// The sensor's mass only sets the scale of k and c (T depends on k/m and c/m); its loading of the structure is
// far below what the data can resolve, so the mass is a known parameter (0.1 % of the body's mass) and the
// candidate estimates the mounting resonance fs_O (Hz) and its damping ratio zs_O, which the data do determine.
// Only offered when O's channels show an unexplained peak: the mounting resonance starts at the first, which is
// one that only O shows where there is one (the engine orders them so).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "diagnosis/expr_build.hpp"
#include "diagnosis/operators/operator_support.hpp"
#include "frontend/model_writer.hpp"

namespace mbgen::diagnosis {

namespace {

// A derived parameter (an expression of others), declared like `param NAME = EXPR "UNIT"`.
ir::Parameter derived(const std::string& name, ir::Expr value, const std::string& unit) {
  ir::Parameter p;
  p.name = name;
  p.value = std::move(value);
  p.derived = true;
  p.unit = unit;
  return p;
}

Extension extend(const OperatorInput& in, const ir::Output& out, const ir::Body& b, int axis, double f_hz) {
  Draft d(in, "sensor_dynamics", out.name);
  const double mass = in.values.of(b.mass);
  const std::string ms = d.add_parameter("ms_" + out.name, 1e-3 * mass, "kg", std::nullopt, std::nullopt,
                                         "mass of the sensor of " + out.name + " (0.1 % of " + b.name +
                                             "'s: its loading is below what the data resolve)",
                                         ir::Role::Known);
  const std::string fs = d.add_parameter("fs_" + out.name, f_hz, "Hz", 0.0, std::nullopt,
                                         "mounting resonance of the sensor of " + out.name);
  const std::string zs = d.add_parameter("zs_" + out.name, 0.05, "", 0.0, 1.0,
                                         "damping ratio of the sensor's mounting resonance");
  const ir::Expr omega = mul(mul(num("2"), sym("pi")), sym(fs));
  const std::string ks = d.names().fresh("ks_" + out.name);
  d.add_parameter(derived(ks, mul(sym(ms), square(omega)), "N/m"), "stiffness of the sensor's mounting");
  const std::string cs = d.names().fresh("cs_" + out.name);
  d.add_parameter(derived(cs, mul(mul(mul(num("2"), sym(zs)), sym(ms)), omega), "N s/m"),
                  "damping of the sensor's mounting");

  const std::string sensor = add_body_on_axial_spring(d, "sensor_" + out.name, ms, out.at.point, axis, b.name, "_mount",
                                                      ks, cs);

  // The output now reads the sensor (at its centre of mass, the measured point), in place in the text.
  ir::Output& measured = *std::find_if(d.model().outputs.begin(), d.model().outputs.end(),
                                       [&](const ir::Output& o) { return o.name == out.name; });
  measured.at.frame = sensor;
  measured.at.point = out.at.point;
  measured.at.has_point = false;
  measured.at.loc = {};
  d.patch().replace_statement(out.loc, out.name + " reads its sensor, not " + b.name + " itself",
                              frontend::write_output(measured));

  char hz[32];
  std::snprintf(hz, sizeof hz, "%.4g", f_hz);
  return d.finish(out.name + " is read through its sensor: a mass " + ms + " on a mounting (resonance " + fs + ", " +
                  "damping ratio " + zs + ", starting at " + hz + " Hz) at the measured point of " + b.name +
                  ", along " + std::string(1, "xyz"[axis]) + ": a second-order low-pass on " + out.name);
}

}  // namespace

std::vector<Extension> sensor_dynamics(const OperatorInput& in) {
  std::vector<Extension> out;
  for (const ir::Output& o : in.model.outputs) {
    const auto peaks = in.ctx.output_peak_hz.find(o.name);
    if (peaks == in.ctx.output_peak_hz.end() || peaks->second.empty()) continue;
    const ir::Body* b = in.model.find_body(o.at.frame);
    if (!b) continue;
    // The sensor's coordinate is along a global axis: an oblique measured direction has no single one.
    const std::optional<int> axis = axis_of(o.direction, in.values);
    if (!axis) continue;
    out.push_back(extend(in, o, *b, *axis, peaks->second.front()));
  }
  return out;
}

}  // namespace mbgen::diagnosis
