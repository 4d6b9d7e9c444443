#include "method_result.hpp"

#include "estimation/output_error.hpp"

#include "mbgen/estimation/identifiability.hpp"
#include "mbgen/dynamics/model_modes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mbgen::methods {

void describe_run(const ModelInfo& info, const std::vector<DataSet>& data, const std::string& method,
                  const Eigen::VectorXd& prior, FitResult& r) {
  r.model = info.name;
  r.data.clear();
  for (const auto& d : data) r.data.push_back(d.file());
  r.method = method;
  r.prior_values = prior;
}

ParameterEstimate parameter_estimate(const ModelInfo& info, int i, const Eigen::VectorXd& prior,
                                     const Eigen::VectorXd& values) {
  const ParameterInfo& pi = info.parameters[static_cast<std::size_t>(i)];
  ParameterEstimate e;
  e.name = pi.name;
  e.unit = pi.unit;
  e.prior = prior[i];
  e.value = values[i];
  return e;
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
  } catch (const std::runtime_error&) {
    result.modes.clear();  // e.g. a singular mass matrix: no modes to report
  }
}

}  // namespace mbgen::methods
