// The model's modes and residues at the measured channels, from the state-space eigenproblem, and the pairing
// of identified modes with them by MAC.
#include "mbgen/modal_pairing.hpp"
#include "mbgen/state_space.hpp"
#include "shape_metrics.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mbgen {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

int index_of(const std::vector<std::string>& names, const std::string& n, const char* what) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == n) return static_cast<int>(i);
  throw std::invalid_argument(std::string("the model has no ") + what + " named `" + n + "`");
}

FrfQuantity quantity_of(const ModelMatrices& m, const std::vector<int>& outputs) {
  FrfQuantity q = FrfQuantity::Unknown;
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const Eigen::Index o = outputs[k];
    const bool d = m.Cd.row(o).any(), v = m.Cv.row(o).any(), a = m.Ca.row(o).any();
    const FrfQuantity here = (d && !v && !a)   ? FrfQuantity::Receptance
                             : (!d && v && !a) ? FrfQuantity::Mobility
                             : (!d && !v && a) ? FrfQuantity::Accelerance
                                               : FrfQuantity::Unknown;
    if (here == FrfQuantity::Unknown || (k > 0 && here != q)) return FrfQuantity::Unknown;
    q = here;
  }
  return q;
}

}  // namespace

ModelModes model_modes(const Model& model, const Eigen::VectorXd& parameters, const ModalData& data) {
  const ModelInfo& info = model.info();
  std::vector<int> outputs(data.outputs.size()), inputs(data.inputs.size());
  for (std::size_t o = 0; o < outputs.size(); ++o) outputs[o] = index_of(info.outputs, data.outputs[o], "output");
  for (std::size_t i = 0; i < inputs.size(); ++i) inputs[i] = index_of(info.inputs, data.inputs[i], "input");
  ModelMatrices m;
  model.evaluate(parameters, m);
  const StateSpace ss = state_space(m);

  // x = [q; q'/s] with s the square root of the stiffness-to-mass scale: the two blocks of A become comparable
  // (the eigenvalues do not change, the eigenvectors are rescaled and the residues with them undone below).
  const Eigen::Index n = m.M.rows();
  const double s = std::sqrt(std::max(1.0, ss.A.bottomLeftCorner(n, n).cwiseAbs().maxCoeff()));
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(2 * n);
  scale.tail(n).setConstant(s);
  const Eigen::MatrixXd A = scale.cwiseInverse().asDiagonal() * ss.A * scale.asDiagonal();
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(A, /*computeEigenvectors=*/true);
  if (eig.info() != Eigen::Success) throw std::runtime_error("the model's eigenvalue iteration did not converge");
  const Eigen::MatrixXcd V = eig.eigenvectors();
  const Eigen::MatrixXcd left = V.partialPivLu().inverse();  // rows: left eigenvectors, left * V = I
  const Eigen::MatrixXcd CV = ss.C.cast<std::complex<double>>() * scale.asDiagonal() * V;
  const Eigen::MatrixXcd WB = left * scale.cwiseInverse().asDiagonal() * ss.B.cast<std::complex<double>>();

  std::vector<Eigen::Index> keep;
  for (Eigen::Index e = 0; e < eig.eigenvalues().size(); ++e)
    if (eig.eigenvalues()[e].imag() >= 0) keep.push_back(e);
  const auto f_of = [&](Eigen::Index e) { return std::abs(eig.eigenvalues()[e]) / kTwoPi; };
  const auto zeta_of = [&](Eigen::Index e) {
    const double mag = std::abs(eig.eigenvalues()[e]);
    return mag > 0 ? -eig.eigenvalues()[e].real() / mag : 0.0;
  };
  std::stable_sort(keep.begin(), keep.end(), [&](Eigen::Index a, Eigen::Index b) {
    return f_of(a) != f_of(b) ? f_of(a) < f_of(b) : zeta_of(a) < zeta_of(b);
  });

  ModelModes out;
  out.quantity = quantity_of(m, outputs);
  out.residues.resize(static_cast<Eigen::Index>(keep.size()), static_cast<Eigen::Index>(data.channels.size()));
  for (std::size_t r = 0; r < keep.size(); ++r) {
    const Eigen::Index e = keep[r];
    out.lambda.push_back(eig.eigenvalues()[e]);
    out.f_hz.push_back(f_of(e));
    out.zeta.push_back(zeta_of(e));
    for (std::size_t c = 0; c < data.channels.size(); ++c) {
      const int o = outputs[static_cast<std::size_t>(data.channels[c].output)];
      const int i = inputs[static_cast<std::size_t>(data.channels[c].input)];
      out.residues(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = CV(o, e) * WB(e, i);
    }
  }
  return out;
}

ModePairing pair_modes(const std::vector<IdentifiedMode>& identified, const ModelModes& model) {
  ModePairing out;
  const Eigen::Index ni = static_cast<Eigen::Index>(identified.size()), nm = model.residues.rows();
  out.mac.resize(ni, nm);
  for (Eigen::Index i = 0; i < ni; ++i) {
    for (Eigen::Index j = 0; j < nm; ++j)
      out.mac(i, j) =
          modal_detail::shape_mac(identified[static_cast<std::size_t>(i)].residues, model.residues.row(j).transpose());
    // Largest MAC; near-ties (e.g. a single channel, where every MAC is 1) go to the nearest frequency.
    Eigen::Index best = -1;
    const double f = identified[static_cast<std::size_t>(i)].f_hz;
    for (Eigen::Index j = 0; j < nm; ++j) {
      const auto fj = model.f_hz[static_cast<std::size_t>(j)];
      if (best < 0 || out.mac(i, j) > out.mac(i, best) + 1e-6 ||
          (std::abs(out.mac(i, j) - out.mac(i, best)) <= 1e-6 &&
           std::abs(fj - f) < std::abs(model.f_hz[static_cast<std::size_t>(best)] - f)))
        best = j;
    }
    out.model_mode.push_back(static_cast<int>(best));
    out.best_mac.push_back(best >= 0 ? out.mac(i, best) : 0.0);
  }
  return out;
}

}  // namespace mbgen
