// The model's modes and residues at the measured channels, from the state-space eigenproblem, and the pairing
// of identified modes with them by MAC.
#include "mbgen/modal_identification/modal_pairing.hpp"
#include "mbgen/dynamics/state_modes.hpp"
#include "shape_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mbgen {

namespace {

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
  const StateModes sm = state_modes(m);
  const Eigen::MatrixXcd CV = sm.ss.C.cast<std::complex<double>>() * sm.right;
  const Eigen::MatrixXcd WB = sm.left * sm.ss.B.cast<std::complex<double>>();

  ModelModes out;
  out.quantity = quantity_of(m, outputs);
  out.residues.resize(static_cast<Eigen::Index>(sm.modes.size()), static_cast<Eigen::Index>(data.channels.size()));
  out.shapes.resize(m.M.rows(), static_cast<Eigen::Index>(sm.modes.size()));
  for (std::size_t r = 0; r < sm.modes.size(); ++r) {
    const Eigen::Index e = sm.modes[r];
    out.lambda.push_back(sm.lambda[e]);
    out.f_hz.push_back(sm.f_hz(e));
    out.zeta.push_back(sm.zeta(e));
    out.shapes.col(static_cast<Eigen::Index>(r)) = sm.right.col(e).head(m.M.rows());
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
  for (std::size_t i = 0; i < out.model_mode.size(); ++i)
    out.shared.push_back(out.model_mode[i] >= 0 &&
                         std::count(out.model_mode.begin(), out.model_mode.end(), out.model_mode[i]) > 1);
  return out;
}

}  // namespace mbgen
