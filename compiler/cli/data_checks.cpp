#include "cli/data_checks.hpp"

#include <mbgen/chain_scores.hpp>
#include <mbgen/frf_noise.hpp>

#include <cmath>
#include <cstdio>

namespace mbgen::cli {

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

// Lines a check needs before it says anything.
constexpr long kMinLines = 10;

}  // namespace

std::vector<std::string> passivity_warnings(const ir::ModelIr& model, const std::vector<DataSet>& data) {
  std::vector<std::string> out;
  for (const ir::Output& o : model.outputs) {
    const ir::Input* in = driven_at(model, o);
    if (!in) continue;
    const int derivatives = o.kind == ir::OutputKind::Displacement ? 0 : o.kind == ir::OutputKind::Velocity ? 1 : 2;
    for (const DataSet& d : data) {
      if (!d.is_frf()) continue;
      const FrfData& frf = std::get<FrfData>(d.content);
      for (const FrfChannel& c : frf.channels) {
        if (c.output != o.name || c.input != in->name) continue;
        const PassivityCheck check = driving_point_passivity(c.values, frf_noise(frf.f_hz, c).sigma, derivatives);
        if (check.lines < kMinLines || !(check.against_share > 0.5)) continue;
        char text[512];
        std::snprintf(text, sizeof text,
                      "%s/%s in %s is a driving point (%s at %s's point, along its direction), but on %.0f %% of the "
                      "%ld lines where its phase is clear it gives out power, which a passive structure cannot: the "
                      "force %s or the sensor %s is recorded with the wrong sign",
                      o.name.c_str(), in->name.c_str(), d.file().c_str(), o.name.c_str(), in->name.c_str(),
                      100 * check.against_share, check.lines, in->name.c_str(), o.name.c_str());
        out.push_back(text);
      }
    }
  }
  return out;
}

}  // namespace mbgen::cli
