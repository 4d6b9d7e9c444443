#include "modal_objectives.hpp"

#include "mbgen/dynamics/model_modes.hpp"
#include "mbgen/modal_identification/modal_pairing.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace mbgen::methods {

ModalComparison compare_modes(const Model& model, const Eigen::VectorXd& p, const ModalData& data,
                              const std::vector<IdentifiedMode>& reference) {
  ModalComparison c;
  ModelModes mm;
  try {
    mm = model_modes(model, p, data);
  } catch (const std::runtime_error&) {
    return c;  // e.g. a singular mass matrix at a trial point
  }
  std::vector<int> oscillating;
  for (std::size_t i = 0; i < mm.lambda.size(); ++i)
    if (mm.lambda[i].imag() > 0) oscillating.push_back(static_cast<int>(i));
  const std::size_t nr = reference.size();
  if (oscillating.size() < nr || nr == 0) return c;
  const auto channels = static_cast<Eigen::Index>(data.channels.size());
  Eigen::MatrixXcd a(channels, static_cast<Eigen::Index>(nr)),
      b(channels, static_cast<Eigen::Index>(oscillating.size()));
  for (std::size_t r = 0; r < nr; ++r) a.col(static_cast<Eigen::Index>(r)) = reference[r].residues;
  for (std::size_t m = 0; m < oscillating.size(); ++m)
    b.col(static_cast<Eigen::Index>(m)) = mm.residues.row(oscillating[m]).transpose();
  const Eigen::MatrixXd mac = modal_assurance_criterion(a, b);
  if (!mac.allFinite()) return c;
  // The pairing score: MAC times the ratio of the residue vectors' norms (smaller over larger). MAC alone is blind
  // to size: a mode the sensors hardly see (the spindle's y modes at its x sensors) has a residue vector of noise
  // size whose MAC with a measured mode can still be high.
  Eigen::MatrixXd score = mac;
  for (Eigen::Index r = 0; r < score.rows(); ++r)
    for (Eigen::Index m = 0; m < score.cols(); ++m) {
      const double na = a.col(r).norm(), nb = b.col(m).norm();
      score(r, m) *= na > 0 && nb > 0 ? std::min(na, nb) / std::max(na, nb) : 0.0;
    }
  c.model_mode.assign(nr, -1);
  c.f_hz.assign(nr, 0);
  c.zeta.assign(nr, 0);
  c.mac.assign(nr, 0);
  c.residues.assign(nr, Eigen::VectorXcd());
  // Greedy: the largest score left pairs its reference and model mode, which then leave the table.
  for (std::size_t k = 0; k < nr; ++k) {
    Eigen::Index r = 0, m = 0;
    if (score.maxCoeff(&r, &m) < 0) return c;
    const int i = oscillating[static_cast<std::size_t>(m)];
    const auto rr = static_cast<std::size_t>(r);
    c.model_mode[rr] = static_cast<int>(m);
    c.mac[rr] = mac(r, m);
    c.f_hz[rr] = mm.f_hz[static_cast<std::size_t>(i)];
    c.zeta[rr] = mm.zeta[static_cast<std::size_t>(i)];
    c.residues[rr] = mm.residues.row(i).transpose();
    score.row(r).setConstant(-1);
    score.col(m).setConstant(-1);
  }
  c.ok = true;
  return c;
}

void structural_residuals(const ModalComparison& c, const std::vector<IdentifiedMode>& reference,
                          const std::vector<int>& modes, Eigen::VectorXd& r) {
  const Eigen::Index channels = reference.empty() ? 0 : reference.front().residues.size();
  const Eigen::Index per = residuals_per_mode(static_cast<int>(channels));
  r.resize(per * static_cast<Eigen::Index>(modes.size()));
  Eigen::Index k = 0;
  for (int m : modes) {
    const auto mm = static_cast<std::size_t>(m);
    const IdentifiedMode& ref = reference[mm];
    const Eigen::VectorXcd& a = c.residues[mm];
    const double na = a.norm(), nb = ref.residues.norm();
    r[k++] = (c.f_hz[mm] - ref.f_hz) / ref.f_hz;
    // Align the model's shape to the reference's phase so that the difference measures shape alone.
    const std::complex<double> overlap = ref.residues.dot(a);  // ref^H a
    const std::complex<double> turn = std::abs(overlap) > 0 ? std::conj(overlap) / std::abs(overlap) : 1.0;
    const Eigen::VectorXcd d = a * (turn / na) - ref.residues / nb;
    for (Eigen::Index i = 0; i < channels; ++i) {
      r[k++] = d[i].real();
      r[k++] = d[i].imag();
    }
    r[k++] = std::log(na / nb);
  }
}

}  // namespace mbgen::methods
