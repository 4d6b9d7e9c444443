// A change in operation explained by a model's parameters
// (runtime/include/mbgen/monitoring/operational_explanation.hpp).
#include "mbgen/monitoring/operational_explanation.hpp"

#include "mbgen/modal_identification/modal_identification.hpp"
#include "mbgen/modal_identification/modal_pairing.hpp"
#include "mbgen/sensitivity/sensitivity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mbgen {

namespace {

double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  const double den = a.squaredNorm() * b.squaredNorm();
  return den > 0 && a.size() == b.size() ? std::norm(a.dot(b)) / den : 0.0;
}

}  // namespace

OperationalModelModes operational_model_modes(const Model& model, const Eigen::VectorXd& values,
                                              const std::vector<std::string>& channels,
                                              const OperationalMonitorResult& monitored, double min_mac) {
  const ModelInfo& info = model.info();
  for (const std::string& c : channels)
    if (info.output_index(c) < 0)
      throw std::invalid_argument("the data's response '" + c + "' is not an output of the model " + info.name);
  // The model's modes at the sensors: per mode, the residues over the channels for each input; the input that
  // excites it most gives its shape C v (up to the factor w^T b).
  ModalData layout;
  layout.outputs = channels;
  layout.inputs = info.inputs;
  for (std::size_t o = 0; o < channels.size(); ++o)
    for (std::size_t i = 0; i < info.inputs.size(); ++i)
      layout.channels.push_back({static_cast<int>(o), static_cast<int>(i), channels[o] + "/" + info.inputs[i]});
  const ModelModes modes = model_modes(model, values, layout);
  const LocalSensitivity local = local_sensitivity(model, values);
  std::vector<Eigen::VectorXcd> shapes;
  std::vector<double> f;
  for (std::size_t r = 0; r < modes.f_hz.size(); ++r) {
    if (!(modes.lambda[r].imag() > 0)) continue;  // local_sensitivity's rows: the oscillating modes in this order
    Eigen::VectorXcd best;
    for (std::size_t i = 0; i < info.inputs.size(); ++i) {
      Eigen::VectorXcd s(static_cast<Eigen::Index>(channels.size()));
      for (std::size_t o = 0; o < channels.size(); ++o)
        s[static_cast<Eigen::Index>(o)] =
            modes.residues(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(o * info.inputs.size() + i));
      if (best.size() == 0 || s.norm() > best.norm()) best = s;
    }
    shapes.push_back(best);
    f.push_back(modes.f_hz[r]);
  }
  OperationalModelModes out;
  out.parameters = local.parameters;
  const std::size_t tracked = monitored.modes.size();
  out.model_mode.assign(tracked, -1);
  out.mac.assign(tracked, 0.0);
  out.f_hz.assign(tracked, std::nan(""));
  out.sensitivity = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(tracked), local.f_normalized.cols());
  struct Candidate {
    double mac;
    std::size_t t, m;
  };
  std::vector<Candidate> candidates;
  for (std::size_t t = 0; t < tracked; ++t)
    for (std::size_t m = 0; m < shapes.size(); ++m) {
      const double value = mac(monitored.modes[t].shape, shapes[m]);
      if (value >= min_mac) candidates.push_back({value, t, m});
    }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.mac > b.mac; });
  std::vector<bool> used(shapes.size(), false);
  for (const Candidate& c : candidates) {
    if (out.model_mode[c.t] >= 0 || used[c.m] || static_cast<Eigen::Index>(c.m) >= local.f_normalized.rows()) continue;
    used[c.m] = true;
    out.model_mode[c.t] = static_cast<int>(c.m);
    out.mac[c.t] = c.mac;
    out.f_hz[c.t] = f[c.m];
    out.sensitivity.row(static_cast<Eigen::Index>(c.t)) = local.f_normalized.row(static_cast<Eigen::Index>(c.m));
  }
  return out;
}

ChangeExplanation explain_change(const OperationalModelModes& model, const OperationalMonitorResult& monitored,
                                 const OperationalChange& change) {
  const Eigen::Index p = static_cast<Eigen::Index>(monitored.modes.size());
  // The relative shifts and their sigmas, over the tracked modes paired with the model.
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(p), weight = Eigen::VectorXd::Zero(p), f(p);
  for (Eigen::Index j = 0; j < p; ++j) {
    f[j] = monitored.modes[static_cast<std::size_t>(j)].f_hz;
    const double percent = change.shift_percent[static_cast<std::size_t>(j)];
    const double sigmas = change.shift_sigma[static_cast<std::size_t>(j)];
    if (model.model_mode[static_cast<std::size_t>(j)] < 0 || !std::isfinite(percent) || !std::isfinite(sigmas)) continue;
    delta[j] = percent / 100;
    // sigma of the relative shift: shift / (shift in sigmas); where the shift is 0, the baseline's residual std.
    const double sd = sigmas != 0 ? std::abs(delta[j] / sigmas)
                                  : monitored.residual_std_hz[static_cast<std::size_t>(j)] / f[j];
    weight[j] = sd > 0 ? 1 / sd : 0;
  }
  // A parameter's effect passes through the same compensation as the shifts (in Hz, then relative again).
  const Eigen::MatrixXd projector = monitored.shift_projector;
  ChangeExplanation out;
  out.dof = std::max(0, monitored.features - 1);
  out.chi2_limit = out.dof > 0 ? out.dof * f_distribution_quantile(0.99, out.dof, 1e9) : 0.0;
  for (Eigen::Index k = 0; k < model.sensitivity.cols(); ++k) {
    const Eigen::VectorXd hz = f.cwiseProduct(model.sensitivity.col(k));
    const Eigen::VectorXd s = (projector * hz).cwiseQuotient(f).cwiseProduct(weight);
    const Eigen::VectorXd d = delta.cwiseProduct(weight);
    if (!(s.squaredNorm() > 1e-300)) continue;  // the frequencies do not depend on it
    ParameterExplanation e;
    e.name = model.parameters[static_cast<std::size_t>(k)];
    e.relative_change = s.dot(d) / s.squaredNorm();
    e.chi2 = (d - e.relative_change * s).squaredNorm();
    e.consistent = out.dof == 0 || e.chi2 <= out.chi2_limit;
    e.plausible = std::abs(e.relative_change) <= 0.5;
    out.parameters.push_back(e);
  }
  std::stable_sort(out.parameters.begin(), out.parameters.end(),
                   [&](const ParameterExplanation& a, const ParameterExplanation& b) {
                     const bool na = a.consistent && a.plausible, nb = b.consistent && b.plausible;
                     if (na != nb) return na;
                     // With one compensated feature every chi2 is 0 but for rounding: the size of the change.
                     if (out.dof > 0 && a.chi2 != b.chi2) return a.chi2 < b.chi2;
                     return std::abs(a.relative_change) < std::abs(b.relative_change);
                   });
  char text[128];
  out.text = "explained by ";
  for (const ParameterExplanation& e : out.parameters) {
    if (!(e.consistent && e.plausible)) break;
    out.named.push_back(e.name);
    std::snprintf(text, sizeof text, "%s%s %+.3g %% (chi2 %.3g)", out.named.size() > 1 ? ", " : "", e.name.c_str(),
                  100 * e.relative_change, e.chi2);
    out.text += text;
  }
  if (out.named.empty()) out.text = "no single parameter of the model explains the shifts";
  if (out.dof == 0 && !out.named.empty())
    out.text += "; one compensated feature: every sensitive parameter fits it, ordered by the change it needs";
  return out;
}

}  // namespace mbgen
