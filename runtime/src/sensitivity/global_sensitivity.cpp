// Sobol indices of the modes' frequencies and damping ratios over ranges of the model's parameters.
#include "mbgen/sensitivity/sensitivity.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace mbgen {

std::vector<ParameterRange> parameter_ranges(const ModelInfo& info, const Eigen::VectorXd& p, double spread,
                                             bool use_bounds) {
  bool any_estimate = false;
  for (const ParameterInfo& pi : info.parameters) any_estimate = any_estimate || pi.role == ParameterRole::Estimate;
  std::vector<ParameterRange> out;
  for (std::size_t i = 0; i < info.parameters.size(); ++i) {
    const ParameterInfo& pi = info.parameters[i];
    if (any_estimate && pi.role != ParameterRole::Estimate) continue;
    ParameterRange r;
    r.name = pi.name;
    r.index = static_cast<int>(i);
    const double v = p[static_cast<Eigen::Index>(i)];
    if (use_bounds) {
      if (!std::isfinite(pi.lower) || !std::isfinite(pi.upper))
        throw std::invalid_argument("parameter `" + pi.name + "` has no finite bounds to sample over");
      r.lo = pi.lower;
      r.hi = pi.upper;
    } else {
      r.lo = std::max(pi.lower, v - spread * std::abs(v));
      r.hi = std::min(pi.upper, v + spread * std::abs(v));
    }
    if (!(r.lo < r.hi)) continue;  // e.g. a parameter at 0: a relative spread gives it no range
    out.push_back(r);
  }
  if (out.empty()) throw std::invalid_argument("no parameter has a range to sample over");
  return out;
}

GlobalSensitivity global_sensitivity(const Model& model, const Eigen::VectorXd& p,
                                     const std::vector<ParameterRange>& ranges, const SobolOptions& options) {
  GlobalSensitivity out;
  out.ranges = ranges;
  out.nominal = oscillating_modes(model, p);
  const int modes = static_cast<int>(out.nominal.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Outputs: f of every nominal mode, then zeta; NaN where the sample's model fails or a mode is not matched.
  const auto evaluate = [&](const Eigen::VectorXd& u) {
    Eigen::VectorXd q = p;
    for (std::size_t i = 0; i < ranges.size(); ++i)
      q[ranges[i].index] = ranges[i].lo + u[static_cast<Eigen::Index>(i)] * (ranges[i].hi - ranges[i].lo);
    Eigen::VectorXd y = Eigen::VectorXd::Constant(2 * modes, nan);
    try {
      const std::vector<Mode> sample = oscillating_modes(model, q);
      const std::vector<int> match = track_modes(out.nominal, sample);
      for (int r = 0; r < modes; ++r) {
        if (match[static_cast<std::size_t>(r)] < 0) continue;
        const Mode& m = sample[static_cast<std::size_t>(match[static_cast<std::size_t>(r)])];
        y[r] = m.f_hz;
        y[modes + r] = m.zeta;
      }
    } catch (const std::runtime_error&) {
      // a singular mass matrix or a failed eigenvalue iteration: this sample says nothing
    }
    return y;
  };
  const SobolIndices all = sobol_indices(evaluate, static_cast<int>(ranges.size()), 2 * modes, options);
  const auto part = [&](int first) {
    SobolIndices s;
    s.first = all.first.middleRows(first, modes);
    s.total = all.total.middleRows(first, modes);
    s.first_std = all.first_std.middleRows(first, modes);
    s.total_std = all.total_std.middleRows(first, modes);
    s.mean = all.mean.segment(first, modes);
    s.variance = all.variance.segment(first, modes);
    s.used = all.used.segment(first, modes);
    s.evaluations = all.evaluations;
    return s;
  };
  out.f = part(0);
  out.zeta = part(modes);
  return out;
}

}  // namespace mbgen
