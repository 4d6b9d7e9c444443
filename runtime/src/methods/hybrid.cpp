// fit_hybrid: the direct estimate refined by output error (docs/methods.md#hybrid).
#include "mbgen/methods/hybrid.hpp"

#include "mbgen/methods/direct.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace mbgen {

namespace {

nlohmann::json estimates(const FitResult& r) {
  nlohmann::json j = nlohmann::json::object();
  for (const ParameterEstimate& e : r.parameters) j[e.name] = e.value;
  return j;
}

}  // namespace

double start_inside_bounds(const ParameterEstimate& estimate, const ParameterInfo& p) {
  if (estimate.at_bound.empty()) return estimate.value;
  const double margin = 1e-3 * (estimate.prior != 0 ? std::abs(estimate.prior) : 1.0);
  return std::min(std::max(estimate.value, p.lower + margin), p.upper - margin);
}

FitResult fit_hybrid(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  const ModelInfo& info = model.info();
  const FitResult direct = fit_direct(model, data, options);

  // The direct estimate becomes the prior of the output-error fit (start 0 and the centre of the random starts); the
  // model's own values (with the user's) are start 1.
  FitOptions refine = options;
  refine.also_start_at.clear();
  for (const ParameterEstimate& e : direct.parameters) {
    const ParameterInfo& p = info.parameters[static_cast<std::size_t>(info.parameter_index(e.name))];
    refine.values[e.name] = start_inside_bounds(e, p);
    refine.also_start_at[e.name] = e.prior;
  }
  refine.starts = std::max(options.starts, 2);
  FitResult result = fit(model, data, refine);
  const std::string output_error = result.method;

  // Priors as the user gave them (the model's values and --set), not the direct estimate the search started from
  // (initial_cost stays the output error at the direct estimate; a parameter output error cannot determine stays
  // at the direct estimate).
  result.prior_values = direct.prior_values;
  for (ParameterEstimate& e : result.parameters)
    e.prior = direct.prior_values[info.parameter_index(e.name)];
  result.method = "hybrid";
  nlohmann::json j;
  j["combines"] = "direct (closed-form equation error) then " + output_error + " started from the direct estimate";
  j["model_prior"] = [&] {
    nlohmann::json p = nlohmann::json::object();
    for (const ParameterEstimate& e : direct.parameters) p[e.name] = e.prior;
    return p;
  }();
  j["direct_estimate"] = estimates(direct);
  j["direct_nrmse"] = direct.nrmse;
  j["output_error_estimate"] = estimates(result);
  j["output_error_nrmse"] = result.nrmse;
  j["output_error_best_start"] = result.best_start == 0 ? "the direct estimate"
                                 : result.best_start == 1 ? "the model's values"
                                                          : "a random start";
  result.method_details = direct.method_details;
  result.method_details["hybrid"] = j.dump();
  return result;
}

}  // namespace mbgen
