#include "diagnosis/engine/new_body_modes.hpp"

#include <algorithm>
#include <complex>

#include <mbgen/dynamics/state_modes.hpp>
#include "numerics/constants.hpp"

namespace mbgen::diagnosis {
namespace {

using numerics::kTwoPi;

bool of_bodies(const std::string& coordinate, const std::vector<std::string>& bodies) {
  return std::any_of(bodies.begin(), bodies.end(), [&](const std::string& b) {
    return coordinate.size() > b.size() && coordinate.compare(0, b.size(), b) == 0 && coordinate[b.size()] == '.';
  });
}

}  // namespace

NewBodyMode best_seen_new_body_mode(const Model& model, const Eigen::VectorXd& p, const std::vector<std::string>& bodies,
                                    const std::vector<ChannelResidual>& channels) {
  const ModelInfo& info = model.info();
  ModelMatrices m;
  model.evaluate(p, m);
  const StateModes sm = state_modes(m);
  const Eigen::Index n = m.M.rows();
  std::vector<Eigen::Index> own;  // the bodies' coordinates
  for (Eigen::Index j = 0; j < n; ++j)
    if (of_bodies(info.coordinates[static_cast<std::size_t>(j)], bodies)) own.push_back(j);
  // Kinetic energy of mode e (velocity lambda phi): its share in the bodies' coordinates.
  std::vector<std::pair<double, Eigen::Index>> by_share;
  for (const Eigen::Index e : sm.modes) {
    const Eigen::VectorXcd phi = sm.right.col(e).head(n);
    const Eigen::VectorXcd m_phi = m.M.cast<std::complex<double>>() * phi;
    const double total = (phi.adjoint() * m_phi)(0).real();
    double mine = 0;
    for (const Eigen::Index j : own) mine += (std::conj(phi[j]) * m_phi[j]).real();
    by_share.emplace_back(total > 0 ? mine / total : 0.0, e);
  }
  std::stable_sort(by_share.begin(), by_share.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  by_share.resize(std::min(by_share.size(), own.size()));
  std::vector<Eigen::Index> oscillating;  // overdamped modes (real eigenvalues) have no resonance
  for (const auto& entry : by_share)
    if (sm.lambda[entry.second].imag() > 0) oscillating.push_back(entry.second);

  NewBodyMode best;
  if (oscillating.empty()) return best;
  best.oscillating = true;
  best.f_hz = sm.f_hz(oscillating.front());
  best.zeta = sm.zeta(oscillating.front());
  const std::vector<ModeTerm> terms = mode_terms(sm, oscillating);
  for (std::size_t r = 0; r < oscillating.size(); ++r) {
    const Eigen::Index e = oscillating[r];
    const ModeTerm& t = terms[r];
    const double f_hz = t.w / kTwoPi;
    for (const ChannelResidual& c : channels) {
      if (c.f_hz.empty() || f_hz < c.f_hz.front() || f_hz > c.f_hz.back()) continue;
      const std::size_t slash = c.channel.find('/');
      if (slash == std::string::npos) continue;
      const int o = info.output_index(c.channel.substr(0, slash)), i = info.input_index(c.channel.substr(slash + 1));
      if (o < 0 || i < 0 || !(t.response(o, i) > 0)) continue;
      const double share = t.share(o, i);
      if (best.channel.empty() || share > best.share) {
        best.f_hz = sm.f_hz(e), best.zeta = sm.zeta(e);
        best.share = share;
        best.channel = c.channel;
      }
    }
  }
  return best;
}

}  // namespace mbgen::diagnosis
