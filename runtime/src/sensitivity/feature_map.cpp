// Feature maps (thesis Fig. 5.34): each mode's (f, zeta) as one parameter sweeps, the modes followed step to step.
#include "mbgen/sensitivity/sensitivity.hpp"

#include <limits>
#include <stdexcept>

namespace mbgen {

FeatureMap feature_map(const Model& model, const Eigen::VectorXd& p, int index, double lo, double hi, int points) {
  const ModelInfo& info = model.info();
  if (index < 0 || index >= static_cast<int>(info.parameters.size()))
    throw std::invalid_argument("feature_map: no parameter " + std::to_string(index));
  if (points < 2) throw std::invalid_argument("feature_map: a sweep needs at least 2 points");
  FeatureMap out;
  out.parameter = info.parameters[static_cast<std::size_t>(index)].name;
  out.values = Eigen::VectorXd::LinSpaced(points, lo, hi);
  Eigen::VectorXd q = p;
  q[index] = lo;
  out.start = oscillating_modes(model, q);
  const Eigen::Index traces = static_cast<Eigen::Index>(out.start.size());
  out.f_hz = Eigen::MatrixXd::Constant(points, traces, std::numeric_limits<double>::quiet_NaN());
  out.zeta = out.f_hz;
  std::vector<Mode> previous = out.start;  // each trace's mode at the last step where it was seen
  for (int k = 0; k < points; ++k) {
    q[index] = out.values[k];
    const std::vector<Mode> modes = k == 0 ? out.start : oscillating_modes(model, q);
    const std::vector<int> match = track_modes(previous, modes);
    for (Eigen::Index t = 0; t < traces; ++t) {
      const int m = match[static_cast<std::size_t>(t)];
      if (m < 0) continue;
      out.f_hz(k, t) = modes[static_cast<std::size_t>(m)].f_hz;
      out.zeta(k, t) = modes[static_cast<std::size_t>(m)].zeta;
      previous[static_cast<std::size_t>(t)] = modes[static_cast<std::size_t>(m)];
    }
  }
  return out;
}

}  // namespace mbgen
