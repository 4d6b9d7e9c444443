// The model's modes at the response channels, their pairing with identified operational modes by MAC, and the
// weighted modal residuals of a model update against them (mbgen/modal_identification/operational_comparison.hpp).
#include "mbgen/modal_identification/operational_comparison.hpp"
#include "mbgen/dynamics/state_modes.hpp"
#include "shape_metrics.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>

namespace mbgen {

namespace {
constexpr double kInvisible = 1e-9;  // |C v| / (|C| |v|) of a mode the sensors do not see
}  // namespace

std::vector<int> model_outputs_of(const ModelInfo& info, const std::vector<std::string>& channels) {
  std::vector<int> out;
  for (const std::string& c : channels) {
    int index = -1;
    for (std::size_t o = 0; o < info.outputs.size(); ++o)
      if (info.outputs[o] == c) index = static_cast<int>(o);
    if (index < 0) throw std::invalid_argument("the model has no output named `" + c + "`");
    out.push_back(index);
  }
  return out;
}

OperationalModelModes operational_model_modes(const Model& model, const Eigen::VectorXd& p,
                                              const std::vector<int>& outputs) {
  ModelMatrices m;
  model.evaluate(p, m);
  const StateModes sm = state_modes(m);
  Eigen::MatrixXd C(static_cast<Eigen::Index>(outputs.size()), sm.ss.C.cols());
  for (std::size_t k = 0; k < outputs.size(); ++k) C.row(static_cast<Eigen::Index>(k)) = sm.ss.C.row(outputs[k]);
  OperationalModelModes out;
  for (const Eigen::Index e : sm.modes) {
    if (!(sm.lambda[e].imag() > 0)) continue;
    Eigen::VectorXcd shape = C.cast<std::complex<double>>() * sm.right.col(e);
    // A mode the sensors do not see (the spindle's y modes at x sensors) has a shape of rounding error, whose MAC
    // with a measured mode can be anything: it has no shape here, and pairs with nothing.
    if (shape.norm() <= kInvisible * C.norm() * sm.right.col(e).norm()) shape.setZero();
    out.f_hz.push_back(sm.f_hz(e));
    out.zeta.push_back(sm.zeta(e));
    out.shapes.push_back(shape);
  }
  return out;
}

std::vector<int> pair_by_mac(const std::vector<OperationalTarget>& targets, const OperationalModelModes& model,
                             std::vector<double>* mac) {
  const std::size_t nt = targets.size(), nm = model.shapes.size();
  Eigen::MatrixXd table(static_cast<Eigen::Index>(nt), static_cast<Eigen::Index>(nm));
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t m = 0; m < nm; ++m)
      table(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(m)) =
          modal_detail::shape_mac(targets[t].shape, model.shapes[m]);
  std::vector<int> out(nt, -1);
  if (mac) mac->assign(nt, 0.0);
  std::vector<bool> target_done(nt, false), model_done(nm, false);
  for (std::size_t t = 0; t < nt; ++t)  // modes without a shape at the sensors pair with nothing
    for (std::size_t m = 0; m < nm; ++m)
      if (!(model.shapes[m].squaredNorm() > 0)) table(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(m)) = -1;
  for (std::size_t k = 0; k < std::min(nt, nm); ++k) {
    // The largest MAC left; a near-tie (within 1e-6: one channel, where every MAC is 1) to the nearest frequency.
    int bt = -1, bm = -1;
    for (std::size_t t = 0; t < nt; ++t) {
      if (target_done[t]) continue;
      for (std::size_t m = 0; m < nm; ++m) {
        if (model_done[m]) continue;
        const double v = table(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(m));
        if (bt < 0) {
          bt = static_cast<int>(t);
          bm = static_cast<int>(m);
          continue;
        }
        const double best = table(bt, bm);
        const double gap = std::abs(targets[t].f_hz - model.f_hz[m]),
                     best_gap = std::abs(targets[static_cast<std::size_t>(bt)].f_hz -
                                         model.f_hz[static_cast<std::size_t>(bm)]);
        if (v > best + 1e-6 || (std::abs(v - best) <= 1e-6 && gap < best_gap)) {
          bt = static_cast<int>(t);
          bm = static_cast<int>(m);
        }
      }
    }
    if (bt < 0 || table(bt, bm) < 0) break;
    out[static_cast<std::size_t>(bt)] = bm;
    if (mac) (*mac)[static_cast<std::size_t>(bt)] = table(bt, bm);
    target_done[static_cast<std::size_t>(bt)] = true;
    model_done[static_cast<std::size_t>(bm)] = true;
  }
  return out;
}

void operational_residuals(const OperationalTarget& target, double model_f_hz, const Eigen::VectorXcd& model_shape,
                           Eigen::Ref<Eigen::VectorXd> r) {
  const Eigen::Index channels = target.shape.size();
  r[0] = (model_f_hz - target.f_hz) / target.f_std_hz;
  const double mm = model_shape.squaredNorm();
  const std::complex<double> a = mm > 0 ? model_shape.dot(target.shape) / mm : 0.0;  // model^H target / |model|^2
  const Eigen::VectorXcd d = target.shape - model_shape * a;
  for (Eigen::Index c = 0; c < channels; ++c) {
    r[1 + 2 * c] = d[c].real() / target.shape_std;
    r[2 + 2 * c] = d[c].imag() / target.shape_std;
  }
}

}  // namespace mbgen
