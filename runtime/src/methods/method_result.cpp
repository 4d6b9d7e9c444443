#include "method_result.hpp"

#include "estimation/output_error.hpp"

#include "mbgen/estimation/identifiability.hpp"
#include "mbgen/dynamics/model_modes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mbgen::methods {

namespace {

// What was run: the model's name, the data's files, the method and the prior.
void describe_run(const ModelInfo& info, const std::vector<DataSet>& data, const MethodOutcome& outcome, FitResult& r) {
  r.model = info.name;
  r.data.clear();
  for (const auto& d : data) r.data.push_back(d.file());
  r.method = outcome.method;
  r.prior_values = outcome.prior;
  r.values = outcome.values;
}

// Each reported parameter: its name, unit, prior and value, and the method's verdicts.
void report_parameters(const ModelInfo& info, const MethodOutcome& outcome, FitResult& r) {
  r.parameters.clear();
  for (const ReportedParameter& p : outcome.parameters) {
    const ParameterInfo& pi = info.parameters[static_cast<std::size_t>(p.index)];
    ParameterEstimate e = p.verdicts;
    e.name = pi.name;
    e.unit = pi.unit;
    e.prior = outcome.prior[p.index];
    e.value = outcome.values[p.index];
    r.parameters.push_back(e);
  }
}

// The covariance, the correlation from it, and (where the method says so) each estimated parameter's std.
void report_covariance(const MethodOutcome& outcome, FitResult& r) {
  r.estimated = outcome.estimated;
  r.covariance = outcome.covariance;
  r.correlation = Eigen::MatrixXd();
  if (outcome.covariance.size() == 0) return;
  const Eigen::VectorXd sd = outcome.covariance.diagonal().cwiseMax(0).cwiseSqrt();
  r.correlation = outcome.covariance.cwiseQuotient(sd * sd.transpose());
  if (!outcome.std_from_covariance) return;
  for (Eigen::Index j = 0; j < sd.size(); ++j)
    for (ParameterEstimate& e : r.parameters)
      if (e.name == r.estimated[static_cast<std::size_t>(j)]) e.std = sd[j];
}

// The output-error numbers of the estimate, as every method reports them: the same residual mbgen::fit minimises,
// so that the methods compare with it and with each other.
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

}  // namespace

ReportedParameter estimated_parameter(int index) {
  ReportedParameter p;
  p.index = index;
  p.verdicts.estimated = true;
  return p;
}

void finish_result(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                   const MethodOutcome& outcome, FitResult& result) {
  describe_run(model.info(), data, outcome, result);
  report_parameters(model.info(), outcome, result);
  report_covariance(outcome, result);
  if (outcome.scored.empty()) result.singular_values = outcome.singular_values;
  score_by_output_error(model, data, options, outcome.scored, outcome.fitted, result);
}

double output_error_cost(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                         const Eigen::VectorXd& values) {
  const estimation::OutputErrorProblem problem(model, data, options.frf_weighting);
  Eigen::VectorXd r;
  problem.evaluate(values, {}, estimation::ResidualKind::Weighted, r, nullptr);
  return r.squaredNorm();
}

}  // namespace mbgen::methods
