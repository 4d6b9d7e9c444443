// sensor_dynamics:O -- output O is not the structure's motion but what its sensor and its instrumentation make of
// it. One candidate per output that the model misses alone or that shows an unexplained peak, with one variant per
// form (the diagnosis fits each and BIC chooses):
//
//   mounting resonance  The sensor as what it physically is: a small mass (an accelerometer on its mounting) on a
//                       spring-damper at the measured point, along the measured direction, and O measures that
//                       mass: T = (c s + k)/(m s^2 + c s + k), a resonance at the mounting frequency. Its mass only
//                       sets the scale of k and c (T depends on k/m and c/m); its loading of the structure is far
//                       below what the data resolve, so the mass is a known parameter (0.1 % of the body's) and the
//                       variant estimates the mounting resonance fs_O and its damping ratio zs_O. Offered where O
//                       shows an unexplained peak, which it starts at (one only O shows first: the engine orders
//                       the peaks so).
//   low-pass            An electrical second-order low-pass (anti-aliasing, signal conditioning): no zero, mainly a
//                       phase lag growing with frequency in the band, no peak (`filter ... lowpass2`).
//   high-pass           AC coupling: a first-order high-pass s/(s + wc), a phase lead and a droop at the band's
//                       low end (`filter ... highpass1`).
//   delay               A pure delay (a converter's group delay, a sampling skew between channels): a phase
//                       linear in frequency (`filter ... delay`, Pade sections enough for the band).
//
// The filters' forms need no peak but an output the model misses alone (ExtensionContext::outputs_with_findings):
// a misfit, a phase trend or a low-frequency discrepancy there brings them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "diagnosis/expr_build.hpp"
#include "diagnosis/operators/operator_support.hpp"
#include "frontend/model_writer.hpp"
#include "numerics/constants.hpp"

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

std::string hz_text(double f) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g Hz", f);
  return text;
}

Extension mounting(const OperatorInput& in, const ir::Output& out, const ir::Body& b, int axis, double f_hz) {
  Draft d(in, "sensor_dynamics", out.name);
  d.set_variant("mounting resonance");
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

  return d.finish(out.name + " is read through its sensor: a mass " + ms + " on a mounting (resonance " + fs + ", " +
                  "damping ratio " + zs + ", starting at " + hz_text(f_hz) + ") at the measured point of " + b.name +
                  ", along " + std::string(1, "xyz"[axis]) + ": a second-order low-pass on " + out.name);
}

// The band the data cover, with a fallback where the engine gave none (a model enumerated without data).
struct Band {
  double lo, hi;
};
Band band_of(const ExtensionContext& ctx) {
  const double hi = ctx.band_hi_hz > 0 ? ctx.band_hi_hz : 1000.0;
  const double lo = ctx.band_lo_hz > 0 && ctx.band_lo_hz < hi ? ctx.band_lo_hz : hi / 100.0;
  return {lo, hi};
}

constexpr double kElectricalMinDamping = 0.38;

Extension lowpass(const OperatorInput& in, const ir::Output& out, double delay_s) {
  Draft d(in, "sensor_dynamics", out.name);
  d.set_variant("low-pass");
  const Band band = band_of(in.ctx);
  // Below its cutoff a low-pass of damping ratio z lags like a delay of 2 z / wc: the residual's delay, where it
  // shows one, gives the start; otherwise a cutoff at twice the band's top, where the lag is still a few degrees.
  const double zeta = 0.7071;
  double fc = delay_s > 0 ? 2 * zeta / (kTwoPi * delay_s) : 2 * band.hi;
  fc = std::clamp(fc, 1.2 * band.lo, 50 * band.hi);
  ir::Filter f;
  f.name = d.names().fresh("lowpass_" + out.name);
  f.output = out.name;
  f.kind = ir::FilterKind::Lowpass2;
  f.cutoff = sym(d.add_parameter("fl_" + out.name, fc, "Hz", band.lo, 100 * band.hi,
                                 "cutoff of a low-pass in the signal chain of " + out.name));
  // An electrical filter's second-order section is damped at least as a Chebyshev with 3 dB ripple (0.38;
  // Butterworth 0.707, Bessel 0.87). Less damped, its peak is a resonance: a sensor's mounting, the variant offered
  // where the output shows one. (Bounded at 0.05, a "low-pass" at 3.1 kHz damped at 0.058, above a 1.5 kHz band,
  // lent xs_front the rising magnitude of a spindle bearing's Maxwell element, outside the library.)
  f.damping = sym(d.add_parameter("zl_" + out.name, zeta, "", kElectricalMinDamping, 3.0,
                                  "its damping ratio (Butterworth: 0.707)"));
  d.add_filter(f);
  return d.finish(out.name + " is recorded through an electrical second-order low-pass (" + f.name +
                  ", starting at a cutoff of " + hz_text(fc) + "): a phase lag growing with frequency");
}

Extension highpass(const OperatorInput& in, const ir::Output& out) {
  Draft d(in, "sensor_dynamics", out.name);
  d.set_variant("high-pass");
  const Band band = band_of(in.ctx);
  const double fc = 0.5 * band.lo;  // a lead of 27 degrees and a droop of 1 dB at the band's lowest line
  ir::Filter f;
  f.name = d.names().fresh("highpass_" + out.name);
  f.output = out.name;
  f.kind = ir::FilterKind::Highpass1;
  f.cutoff = sym(d.add_parameter("fh_" + out.name, fc, "Hz", 1e-3 * band.lo, band.hi,
                                 "cutoff of an AC coupling (first-order high-pass) of " + out.name));
  d.add_filter(f);
  return d.finish(out.name + " is AC-coupled: a first-order high-pass (" + f.name + ", starting at a cutoff of " +
                  hz_text(fc) + "), a phase lead and a droop at the band's low end");
}

Extension delay(const OperatorInput& in, const ir::Output& out, double delay_s) {
  Draft d(in, "sensor_dynamics", out.name);
  d.set_variant("delay");
  const Band band = band_of(in.ctx);
  const double w_hi = kTwoPi * band.hi;
  const double tau = delay_s > 0 ? delay_s : 0.2 / w_hi;  // the residual's delay, or 0.2 rad at the band's top
  // Enough Pade sections that the delay stays accurate (phase within 1 %, w tau/N < 1.7) up to four times the
  // start value over the whole band; the bound keeps the estimate where the sections are accurate. Without the
  // residual's delay, up to half a cycle at the band's top: a fit that bends the structure hides a delay's phase
  // trend, and with the reach of four times 0.2 rad, 0.8 rad, mdof2's delays of 0.93 ms (2.3 rad at 400 Hz) were
  // out of bounds and ended `unexplained`.
  const double reach = delay_s > 0 ? 4 * tau : numerics::kPi / w_hi;
  const int sections = std::clamp(static_cast<int>(std::ceil(reach * w_hi / 1.7)), 1, 16);
  const double tau_max = sections * 1.7 / w_hi;
  ir::Filter f;
  f.name = d.names().fresh("delay_" + out.name);
  f.output = out.name;
  f.kind = ir::FilterKind::Delay;
  f.sections = sections;
  const std::string td = d.add_parameter("td_" + out.name, std::min(tau, 0.5 * tau_max), "s", 0.0, tau_max,
                                         "delay of " + out.name + " against the input (bounded where its " +
                                             std::to_string(sections) + " Pade section(s) stay accurate over the band)");
  f.time = sym(td);
  d.nests_near_zero(td, std::min(tau, 0.5 * tau_max));
  d.add_filter(f);
  char text[64];
  std::snprintf(text, sizeof text, "%.3g s", tau);
  return d.finish(out.name + " is recorded late: a pure delay (" + f.name + ", starting at " + text +
                  "), a phase linear in frequency");
}

}  // namespace

std::vector<Extension> sensor_dynamics(const OperatorInput& in) {
  std::vector<Extension> out;
  // A sensor's or its signal chain's dynamics change its own output only: the same kind of misfit on every output
  // is the structure's or the input's. So the last output without a filter of its own gets none (an mdof2 support
  // with a Maxwell element, outside the library, was "explained" by a delay on d2 and then one on d1).
  std::set<std::string> filtered;
  for (const ir::Filter& f : in.model.filters) filtered.insert(f.output);
  const bool last_unfiltered = in.model.outputs.size() > 1 && filtered.size() + 1 == in.model.outputs.size();
  for (const ir::Output& o : in.model.outputs) {
    const ir::Body* b = in.model.find_body(o.at.frame);
    if (!b) continue;
    if (last_unfiltered && !filtered.count(o.name)) continue;
    const auto peaks = in.ctx.output_peak_hz.find(o.name);
    const bool has_peak = peaks != in.ctx.output_peak_hz.end() && !peaks->second.empty();
    // The signal chain's forms only where the model misses this output alone: a filter changes its own output
    // and nothing else. A peak that the priors misplace shows on every output, so a peak alone brings only the
    // mounting resonance. (An mdof2 support with a Maxwell element, outside the library: a 10 us delay on d1,
    // offered for the second mode's peak, which the priors put elsewhere, took the phase of that mode and a
    // damper between the masses then completed a wrong extension.)
    const bool missed_alone = in.ctx.outputs_with_findings.count(o.name) > 0;
    if (!has_peak && !missed_alone) continue;
    const auto delay_it = in.ctx.output_delay_s.find(o.name);
    const double delay_s = delay_it == in.ctx.output_delay_s.end() ? 0.0 : delay_it->second;
    // The mounting resonance needs a body coordinate along a global axis: an oblique direction has no single one.
    const std::optional<int> axis = axis_of(o.direction, in.values);
    if (has_peak && axis) out.push_back(mounting(in, o, *b, *axis, peaks->second.front()));
    if (!missed_alone) continue;
    out.push_back(lowpass(in, o, delay_s));
    out.push_back(highpass(in, o));
    out.push_back(delay(in, o, delay_s));
  }
  return out;
}

}  // namespace mbgen::diagnosis
