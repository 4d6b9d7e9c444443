#include "fit_inputs.hpp"

#include "value_checks.hpp"

#include <algorithm>

namespace mbgen::estimation {

Eigen::VectorXd checked_prior(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  const ModelInfo& info = model.info();
  Eigen::VectorXd prior = info.default_values();
  for (const auto& [name, value] : options.values) {
    const int idx = info.parameter_index(name);
    if (idx < 0) throw FitError("fit: --set " + name + ": the model has no parameter " + name);
    prior[idx] = value;
  }
  check_parameter_values(model, prior, options.values.empty() ? "the model's values" : "the values set");
  check_data_set_values(model, prior, data);
  check_measured_signals(model, data);
  return prior;
}

std::vector<int> candidate_parameters(const ModelInfo& info, const FitOptions& options) {
  std::vector<int> out;
  if (options.estimate.empty()) {
    for (std::size_t i = 0; i < info.parameters.size(); ++i)
      if (info.parameters[i].role == ParameterRole::Estimate) out.push_back(static_cast<int>(i));
    return out;
  }
  for (const auto& name : options.estimate) {
    const int idx = info.parameter_index(name);
    if (idx < 0) throw FitError("fit: the model has no parameter " + name + " (asked to estimate it)");
    out.push_back(idx);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

IdentifiabilityOptions identifiability_options(const FitOptions& options) {
  IdentifiabilityOptions id;
  id.zero_tolerance = options.zero_tolerance;
  id.rank_tolerance = options.rank_tolerance;
  return id;
}

}  // namespace mbgen::estimation
