#include "mbgen/residuals/same_response.hpp"

#include <mbgen/dynamics/frf.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace mbgen {

std::vector<double> probe_frequencies(const std::vector<DataSet>& data) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const DataSet& d : data) {
    if (const auto* frf = std::get_if<FrfData>(&d.content)) {
      for (double f : frf->f_hz)
        if (f > 0) lo = std::min(lo, f), hi = std::max(hi, f);
    } else {
      const TimeRecord& r = std::get<TimeRecord>(d.content);
      if (r.samples() < 2) continue;
      lo = std::min(lo, 1.0 / (r.t[r.samples() - 1] - r.t[0]));
      hi = std::max(hi, 0.4 / r.dt());
    }
  }
  if (!(lo < hi)) lo = 1, hi = 1000;  // no usable band: any generic points serve the identity test
  // Log-spaced, each nudged off the grid by an irregular fraction so that no probe sits on a data line (where an
  // undamped model might have its resonance by construction).
  std::vector<double> probes;
  constexpr int count = 8;
  for (int i = 0; i < count; ++i) {
    const double u = (i + 0.5 + 0.123 * std::sin(7.0 * (i + 1))) / count;
    probes.push_back(lo * std::pow(hi / lo, u));
  }
  return probes;
}

namespace {

bool same_signature(const ModelInfo& a, const ModelInfo& b, const std::set<std::string>& names_in_use) {
  if (a.inputs != b.inputs || a.outputs != b.outputs || a.parameters.size() != b.parameters.size()) return false;
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    const ParameterInfo &p = a.parameters[i], &q = b.parameters[i];
    // Exact comparison on purpose: the two come from the same declarations, or they are different models.
    if (p.role != q.role || p.unit != q.unit || p.value != q.value || p.lower != q.lower || p.upper != q.upper)
      return false;
    if (p.name != q.name && (names_in_use.count(p.name) || names_in_use.count(q.name))) return false;
  }
  return true;
}

// A random parameter vector around the defaults: each value scaled by a factor in [e^-0.4, e^0.4] (a zero
// moved to +-0.1), kept within the bounds. The draws are written out (53 bits of a std::mt19937_64) so that
// they are the same on every standard library.
Eigen::VectorXd random_point(const ModelInfo& info, std::mt19937_64& engine) {
  Eigen::VectorXd p(static_cast<Eigen::Index>(info.parameters.size()));
  for (std::size_t i = 0; i < info.parameters.size(); ++i) {
    const ParameterInfo& pi = info.parameters[i];
    const double u = 2.0 * static_cast<double>(engine() >> 11) * 0x1.0p-53 - 1.0;
    const double v = pi.value == 0 ? 0.1 * u : pi.value * std::exp(0.4 * u);
    p[static_cast<Eigen::Index>(i)] = std::clamp(v, pi.lower, pi.upper);
  }
  return p;
}

}  // namespace

bool same_response(const Model& a, const Model& b, const std::vector<double>& probe_hz,
                   const std::set<std::string>& names_in_use) {
  if (!same_signature(a.info(), b.info(), names_in_use)) return false;
  std::mt19937_64 engine(20261122);
  for (int point = 0; point < 3; ++point) {
    const Eigen::VectorXd p = random_point(a.info(), engine);
    FrfResult ha, hb;
    try {
      ha = frf(a, p, probe_hz);
      hb = frf(b, p, probe_hz);
    } catch (const std::runtime_error&) {  // DynamicsError at this point; a logic_error is a bug and goes on
      return false;
    }
    // Per channel (output, input): the largest magnitude over the probes sets the scale, so that a channel's
    // anti-resonance is compared on the channel's own scale, not on its tiny local value.
    const Eigen::Index outputs = ha.H.front().rows(), inputs = ha.H.front().cols();
    for (Eigen::Index o = 0; o < outputs; ++o)
      for (Eigen::Index i = 0; i < inputs; ++i) {
        double scale = 0;
        for (std::size_t k = 0; k < probe_hz.size(); ++k)
          scale = std::max({scale, std::abs(ha.H[k](o, i)), std::abs(hb.H[k](o, i))});
        for (std::size_t k = 0; k < probe_hz.size(); ++k)
          if (!(std::abs(ha.H[k](o, i) - hb.H[k](o, i)) <= 1e-8 * scale)) return false;
      }
  }
  return true;
}

}  // namespace mbgen
