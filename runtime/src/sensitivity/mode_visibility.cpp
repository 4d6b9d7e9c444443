// Which channel sees each mode best: the mode's share of the channel's response at the mode's frequency, from the
// exact partial fractions H(s) = D + sum_e C v_e w_e^T B / (s - lambda_e) over every eigenvalue.
#include "mbgen/sensitivity/sensitivity.hpp"
#include "mbgen/dynamics/state_modes.hpp"

#include <cmath>

namespace mbgen {

ModeVisibility mode_visibility(const Model& model, const Eigen::VectorXd& p) {
  const ModelInfo& info = model.info();
  ModelMatrices m;
  model.evaluate(p, m);
  const StateModes sm = state_modes(m);
  const Eigen::Index outputs = sm.ss.C.rows(), inputs = sm.ss.B.cols();
  std::vector<Eigen::Index> eig;
  for (const Eigen::Index e : sm.modes)
    if (sm.lambda[e].imag() > 0) eig.push_back(e);

  ModeVisibility out;
  for (Eigen::Index o = 0; o < outputs; ++o)
    for (Eigen::Index i = 0; i < inputs; ++i)
      out.channels.push_back(info.outputs[static_cast<std::size_t>(o)] + "/" +
                             info.inputs[static_cast<std::size_t>(i)]);
  const Eigen::Index modes = static_cast<Eigen::Index>(eig.size()), channels = outputs * inputs;
  out.dominance.resize(modes, channels);
  out.peak.resize(modes, channels);
  const std::vector<ModeTerm> terms = mode_terms(sm, eig);
  for (Eigen::Index r = 0; r < modes; ++r) {
    const ModeTerm& t = terms[static_cast<std::size_t>(r)];
    for (Eigen::Index o = 0; o < outputs; ++o)
      for (Eigen::Index i = 0; i < inputs; ++i) {
        const Eigen::Index c = o * inputs + i;
        out.peak(r, c) = t.term(o, i);
        out.dominance(r, c) = t.share(o, i);
      }
    Eigen::Index best = 0;
    if (channels > 0) out.dominance.row(r).maxCoeff(&best);
    out.best.push_back(static_cast<int>(best));
  }
  return out;
}

}  // namespace mbgen
