#include "method_result.hpp"

#include "../estimation/output_error.hpp"
#include "../estimation/value_checks.hpp"

#include "mbgen/identifiability.hpp"
#include "mbgen/modal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mbgen::methods {

Eigen::VectorXd checked_prior(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  const ModelInfo& info = model.info();
  Eigen::VectorXd prior = info.default_values();
  for (const auto& [name, value] : options.values) {
    const int idx = info.parameter_index(name);
    if (idx < 0) throw FitError("fit: --set " + name + ": the model has no parameter " + name);
    prior[idx] = value;
  }
  estimation::check_parameter_values(model, prior, options.values.empty() ? "the model's values" : "the values set");
  estimation::check_data_set_values(model, prior, data);
  estimation::check_measured_signals(model, data);
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

double output_error_cost(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                         const Eigen::VectorXd& values) {
  const estimation::OutputErrorProblem problem(model, data, options.frf_weighting);
  Eigen::VectorXd r;
  problem.evaluate(values, {}, estimation::ResidualKind::Weighted, r, nullptr);
  return r.squaredNorm();
}

void score_by_output_error(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                           const std::vector<int>& candidates, int fitted, FitResult& result) {
  const estimation::OutputErrorProblem problem(model, data, options.frf_weighting);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  problem.evaluate(result.prior_values, {}, estimation::ResidualKind::Weighted, r, nullptr);
  result.initial_cost = r.squaredNorm();
  problem.evaluate(result.values, candidates, estimation::ResidualKind::Weighted, r, &J);
  const double n = double(problem.residual_count()), k = double(fitted);
  result.residual_count = static_cast<long>(problem.residual_count());
  result.cost = r.squaredNorm();
  result.residual_variance = n > k ? result.cost / (n - k) : std::numeric_limits<double>::quiet_NaN();
  result.nrmse = problem.measured_sum_squares() > 0 ? std::sqrt(result.cost / problem.measured_sum_squares())
                                                    : std::numeric_limits<double>::quiet_NaN();
  result.bic = n * std::log(std::max(result.cost, std::numeric_limits<double>::min()) / n) + k * std::log(n);
  for (std::size_t j = 0; j < candidates.size(); ++j) {
    const double v = std::abs(result.values[candidates[j]]);
    J.col(static_cast<Eigen::Index>(j)) *= v > 0 ? v : 1.0;
  }
  IdentifiabilityOptions id;
  id.zero_tolerance = options.zero_tolerance;
  id.rank_tolerance = options.rank_tolerance;
  if (!candidates.empty()) result.singular_values = analyse_identifiability(J, id).singular_values;
  ModelMatrices m;
  model.evaluate(result.values, m);
  try {
    result.modes = modal_analysis(m.M, m.C, m.K);
  } catch (const std::exception&) {
    result.modes.clear();  // e.g. a singular mass matrix: no modes to report
  }
}

}  // namespace mbgen::methods
