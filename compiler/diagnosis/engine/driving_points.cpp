#include "diagnosis/engine/driving_points.hpp"

#include <mbgen/data/frf_noise.hpp>

#include <cstdio>

#include "diagnosis/model_values.hpp"

namespace mbgen::diagnosis {

namespace {

bool same_text(const ir::Vec3& a, const ir::Vec3& b) {
  for (int k = 0; k < 3; ++k)
    if (ir::to_string(a[static_cast<std::size_t>(k)]) != ir::to_string(b[static_cast<std::size_t>(k)])) return false;
  return true;
}

// The force input whose point and direction `out` measures at, if any.
const ir::Input* driven_at(const ir::ModelIr& model, const ir::Output& out) {
  for (const ir::Input& in : model.inputs)
    if (in.kind == ir::InputKind::Force && in.at.frame == out.at.frame && same_text(in.at.point, out.at.point) &&
        same_text(in.direction.vector, out.direction.vector))
      return &in;
  return nullptr;
}

// The sign the model itself declares between a driving point's recorded FRF and the structure's: the input's gain
// times the output's gain filters (recorded output g_out y over recorded force g_in F is g_out / g_in times H). A
// model that says the force or the sensor is recorded reversed expects data that seem to give out power.
double declared_sign(const ir::ModelIr& model, const ir::Input& in, const ir::Output& out) {
  const ModelValues values(model, {});
  double product = 1;
  if (in.gain) product *= values.of(*in.gain);
  for (const ir::Filter& f : model.filters)
    if (f.output == out.name && f.kind == ir::FilterKind::Gain && f.factor) product *= values.of(*f.factor);
  return product < 0 ? -1.0 : 1.0;
}

// Lines a check needs before it says anything.
constexpr long kMinLines = 10;

}  // namespace

std::vector<ReversedDrivingPoint> reversed_driving_points(const ir::ModelIr& model, const std::vector<DataSet>& data) {
  std::vector<ReversedDrivingPoint> out;
  for (const ir::Output& o : model.outputs) {
    const ir::Input* in = driven_at(model, o);
    if (!in) continue;
    const int derivatives = o.kind == ir::OutputKind::Displacement ? 0 : o.kind == ir::OutputKind::Velocity ? 1 : 2;
    const double sign = declared_sign(model, *in, o);
    for (const DataSet& d : data) {
      if (!d.is_frf()) continue;
      const FrfData& frf = std::get<FrfData>(d.content);
      for (const FrfChannel& c : frf.channels) {
        if (c.output != o.name || c.input != in->name) continue;
        const PassivityCheck check = driving_point_passivity(sign * c.values, frf_noise(frf.f_hz, c).sigma,
                                                             derivatives);
        if (check.lines < kMinLines || !(check.against_share > 0.5)) continue;
        out.push_back({o.name, in->name, d.file(), check});
      }
    }
  }
  return out;
}

std::string describe(const ReversedDrivingPoint& p) {
  char text[1024];
  std::snprintf(text, sizeof text,
                "%s/%s in %s is a driving point (%s at %s's point, along its direction), but on %.0f %% of the "
                "%ld lines where its phase is clear it gives out power, which a passive structure cannot: the "
                "force %s or the sensor %s is recorded with the wrong sign",
                p.output.c_str(), p.input.c_str(), p.file.c_str(), p.output.c_str(), p.input.c_str(),
                100 * p.check.against_share, p.check.lines, p.input.c_str(), p.output.c_str());
  return text;
}

}  // namespace mbgen::diagnosis
