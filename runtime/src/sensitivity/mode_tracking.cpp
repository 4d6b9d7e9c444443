// The oscillating modes of a model and how modes are followed from one parameter set to another.
#include "mbgen/modal_identification/modal_identification.hpp"
#include "mbgen/sensitivity/sensitivity.hpp"
#include "mbgen/dynamics/state_modes.hpp"

#include <algorithm>
#include <cmath>

namespace mbgen {

namespace {

double displacement_mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  const double aa = a.squaredNorm(), bb = b.squaredNorm();
  return aa > 0 && bb > 0 ? std::norm(a.dot(b)) / (aa * bb) : 0.0;
}

}  // namespace

std::vector<Mode> oscillating_modes(const Model& model, const Eigen::VectorXd& p) {
  ModelMatrices m;
  model.evaluate(p, m);
  const StateModes sm = state_modes(m);
  const Eigen::Index n = m.M.rows();
  std::vector<Mode> out;
  for (const Eigen::Index e : sm.modes) {
    if (!(sm.lambda[e].imag() > 0)) continue;
    Mode mode;
    mode.eigenvalue = sm.lambda[e];
    mode.f_hz = sm.f_hz(e);
    mode.zeta = sm.zeta(e);
    mode.shape = sm.right.col(e).head(n);
    // Largest entry exactly 1, as modal_analysis does: removes the solver's arbitrary complex factor.
    Eigen::Index largest = 0;
    mode.shape.cwiseAbs().maxCoeff(&largest);
    const std::complex<double> scale = mode.shape[largest];
    if (std::abs(scale) > 0) mode.shape /= scale;
    out.push_back(std::move(mode));
  }
  return out;
}

std::vector<int> track_modes(const std::vector<Mode>& reference, const std::vector<Mode>& modes) {
  // All pairs by decreasing MAC (ties: the reference's order, then the candidates'), taken greedily.
  struct Pair {
    double mac;
    std::size_t r, m;
  };
  std::vector<Pair> pairs;
  for (std::size_t r = 0; r < reference.size(); ++r)
    for (std::size_t m = 0; m < modes.size(); ++m)
      pairs.push_back({displacement_mac(reference[r].shape, modes[m].shape), r, m});
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.mac > b.mac; });
  std::vector<int> out(reference.size(), -1);
  std::vector<bool> taken(modes.size(), false);
  for (const Pair& p : pairs) {
    if (out[p.r] >= 0 || taken[p.m]) continue;
    out[p.r] = static_cast<int>(p.m);
    taken[p.m] = true;
  }
  return out;
}

}  // namespace mbgen
