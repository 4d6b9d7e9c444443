// start_from_modes (mbgen/methods/modal_start.hpp): the modal method's objectives solved once, jointly, from the
// priors, to place a start for the output-error fit.
#include "mbgen/methods/modal_start.hpp"

#include "method_result.hpp"
#include "modal_configurations.hpp"
#include "modal_solve.hpp"

#include "mbgen/estimation/spectral_companion.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "text/string_format.hpp"

namespace mbgen {

namespace {

using methods::ModalConfiguration;
using methods::ModeRef;

// The damping least squares' relinearisations (the modal method's count).
constexpr int kDampingIterations = 4;

// Leaves out a configuration's weakest modes (smallest residue norm) until the model at p has as many oscillating
// modes as it keeps: a model lacking a mode the data show still gets a start from the others.
void keep_pairable(const Model& model, const Eigen::VectorXd& p, ModalConfiguration& cf) {
  while (!cf.reference.empty() &&
         !methods::compare_modes(model, methods::in_configuration(cf, p), cf.data, cf.reference).ok) {
    const auto weakest = std::min_element(cf.reference.begin(), cf.reference.end(), [](const auto& a, const auto& b) {
      return a.residues.norm() < b.residues.norm();
    });
    cf.reference.erase(weakest);
  }
}

std::string range_text(const std::vector<double>& f) {
  const auto [lo, hi] = std::minmax_element(f.begin(), f.end());
  return f.size() == 1 ? detail::format("%.4g Hz", *lo) : detail::format("%.4g-%.4g Hz", *lo, *hi);
}

ModalStart place(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  ModalStart out;
  const ModelInfo& info = model.info();
  std::vector<DataSet> frfs = data;
  if (std::any_of(data.begin(), data.end(), [](const DataSet& d) { return !d.is_frf(); })) {
    auto companion = estimation::spectral_companion(info, data);
    if (!companion) {
      out.summary = "no start from the data's modes: the records are too short for FRF estimates";
      return out;
    }
    frfs = std::move(companion->data);
  }
  std::vector<ModalConfiguration> configurations = methods::group_configurations(info, frfs);
  const Eigen::VectorXd prior = methods::checked_prior(model, data, options);
  const std::vector<int> candidates = methods::candidate_parameters(info, options);
  const methods::ParameterClasses classes = methods::classify_parameters(model, prior, candidates);
  if (classes.structural.empty()) {
    out.summary = "no start from the data's modes: no mass or stiffness parameter is estimated";
    return out;
  }
  methods::identify_reference_modes(model, prior, configurations);
  std::vector<ModeRef> modes;
  for (std::size_t c = 0; c < configurations.size(); ++c) {
    keep_pairable(model, prior, configurations[c]);
    for (std::size_t m = 0; m < configurations[c].reference.size(); ++m) {
      modes.push_back({static_cast<int>(c), static_cast<int>(m)});
      out.f_hz.push_back(configurations[c].reference[m].f_hz);
    }
  }
  if (modes.empty()) {
    out.summary = "no start from the data's modes: the FRFs show no mode the model could be paired with";
    return out;
  }
  const methods::ModalProblem pr{model, configurations, modes};
  std::vector<int> all(modes.size());
  std::iota(all.begin(), all.end(), 0);
  Eigen::VectorXd x(static_cast<Eigen::Index>(classes.structural.size())), r;
  for (std::size_t j = 0; j < classes.structural.size(); ++j)
    x[static_cast<Eigen::Index>(j)] = std::log(prior[classes.structural[j]]);
  if (!methods::residuals_at(pr, prior, classes.structural, all, x, r)) {
    out.summary = "no start from the data's modes: the model's modes at the priors cannot be paired with them";
    return out;
  }
  out.cost_at_prior = r.squaredNorm();
  const methods::LocalOptimum o = methods::local_fit(pr, prior, prior, classes.structural, all, options);
  if (!(o.cost < out.cost_at_prior)) {
    out.summary = detail::format("no start from the data's modes: the modes at the priors already agree as well as "
                                 "the solve could make them (misfit %.3g)", out.cost_at_prior);
    return out;
  }
  Eigen::VectorXd p = o.p;
  std::string damping_note;
  try {
    nlohmann::json log = nlohmann::json::array();
    methods::solve_damping(pr, classes.damping, prior, kDampingIterations, p, log);
  } catch (const FitError&) {
    // The damping ratios cannot separate the damping parameters (or the modes no longer pair at the new values):
    // they stay at their priors, which the fit then moves.
    for (int i : classes.damping) p[i] = prior[i];
    damping_note = " (the damping ratios do not separate the damping parameters: those stay at their priors)";
  }
  out.cost = o.cost;
  for (int i : classes.structural) out.values[info.parameters[static_cast<std::size_t>(i)].name] = p[i];
  for (int i : classes.damping) out.values[info.parameters[static_cast<std::size_t>(i)].name] = p[i];
  out.summary = detail::format("%zu mode%s (%s): %zu mass/stiffness and %zu damping parameter%s placed, modal misfit "
                               "%.3g -> %.3g%s",
                               modes.size(), modes.size() == 1 ? "" : "s", range_text(out.f_hz).c_str(),
                               classes.structural.size(), classes.damping.size(),
                               classes.damping.size() == 1 ? "" : "s", out.cost_at_prior, out.cost,
                               damping_note.c_str());
  return out;
}

}  // namespace

ModalStart start_from_modes(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  try {
    return place(model, data, options);
  } catch (const std::runtime_error& e) {  // FitError, DataError, DynamicsError: data this start cannot use
    ModalStart none;
    none.summary = std::string("no start from the data's modes: ") + e.what();
    return none;
  } catch (const std::invalid_argument& e) {
    ModalStart none;
    none.summary = std::string("no start from the data's modes: ") + e.what();
    return none;
  }
}

void start_first_at(const std::map<std::string, double>& values, FitOptions& options) {
  if (values.empty()) return;
  if (!options.also_start_at.empty())
    options.further_starts_at.insert(options.further_starts_at.begin(), options.also_start_at);
  options.also_start_at = values;
  options.starts = std::max(options.starts, 2);
}

}  // namespace mbgen
