#include "mbgen/fit.hpp"

#include "fit_setup.hpp"
#include "levenberg_marquardt.hpp"
#include "multistart.hpp"
#include "output_error.hpp"
#include "mbgen/spectral_companion.hpp"

#include "mbgen/identifiability.hpp"
#include "mbgen/parameterization.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <optional>

namespace mbgen {

using estimation::LmOptions;
using estimation::LmResult;
using estimation::OutputErrorProblem;
using estimation::ResidualFunction;
using estimation::ResidualKind;

namespace {

// The fit over one set of free parameters, in internal coordinates.
class Estimator {
 public:
  Estimator(const OutputErrorProblem& problem, const Eigen::VectorXd& prior, std::vector<ParameterTransform> transforms)
      : problem_(problem), prior_(prior), transforms_(std::move(transforms)) {}

  Eigen::VectorXd full_values(const std::vector<int>& free, const Eigen::VectorXd& theta) const {
    return estimation::physical_values(prior_, free, transforms_, theta);
  }
  Eigen::VectorXd internal(const std::vector<int>& free, const Eigen::VectorXd& full) const {
    return estimation::internal_values(free, transforms_, full);
  }

  ResidualFunction function(const std::vector<int>& free, ResidualKind kind) const {
    return [this, free, kind](const Eigen::VectorXd& theta, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
      const Eigen::VectorXd full = full_values(free, theta);
      try {
        problem_.evaluate(full, free, kind, r, J);
      } catch (const std::exception&) {
        return false;  // e.g. a singular mass matrix far from the prior: a failed trial step
      }
      if (J)
        for (std::size_t j = 0; j < free.size(); ++j)
          J->col(static_cast<Eigen::Index>(j)) *=
              transforms_[static_cast<std::size_t>(free[j])].derivative(theta[static_cast<Eigen::Index>(j)]);
      return true;
    };
  }

  // Jacobian in physical units with columns multiplied by `scale` (relative sensitivities).
  Eigen::MatrixXd scaled_jacobian(const std::vector<int>& free, const Eigen::VectorXd& full,
                                  Eigen::VectorXd* scale_out, Eigen::VectorXd* r_out = nullptr) const {
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    problem_.evaluate(full, free, ResidualKind::Weighted, r, &J);
    Eigen::VectorXd scale(static_cast<Eigen::Index>(free.size()));
    for (std::size_t j = 0; j < free.size(); ++j) {
      const double v = std::abs(full[free[j]]);
      scale[static_cast<Eigen::Index>(j)] = v > 0 ? v : transforms_[static_cast<std::size_t>(free[j])].scale;
    }
    if (scale_out) *scale_out = scale;
    if (r_out) *r_out = r;
    return J * scale.asDiagonal();
  }

 private:
  const OutputErrorProblem& problem_;
  Eigen::VectorXd prior_;
  std::vector<ParameterTransform> transforms_;
};

std::vector<int> select(const std::vector<int>& cols, const std::vector<bool>& keep) {
  std::vector<int> out;
  for (std::size_t i = 0; i < cols.size(); ++i)
    if (keep[i]) out.push_back(cols[i]);
  return out;
}

}  // namespace

FitResult fit(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  const ModelInfo& info = model.info();
  const estimation::FitSetup setup = estimation::prepare_fit(model, data, options);
  const Eigen::VectorXd& prior = setup.prior;
  const std::vector<int>& candidates = setup.candidates;
  const std::vector<ParameterTransform>& transforms = setup.transforms;
  const OutputErrorProblem problem(model, data, options.frf_weighting);
  const Estimator estimator(problem, prior, transforms);
  IdentifiabilityOptions id_options;
  id_options.zero_tolerance = options.zero_tolerance;
  id_options.rank_tolerance = options.rank_tolerance;

  FitResult result;
  result.model = info.name;
  for (const auto& d : data) result.data.push_back(d.file());
  result.method = problem.has_frf() ? (problem.has_time() ? "mixed-output-error" : "frf-output-error")
                                    : "time-output-error";
  result.prior_values = prior;
  result.residual_count = static_cast<long>(problem.residual_count());

  // Identifiability at the prior: drop what the data cannot determine before searching.
  std::vector<bool> identifiable(candidates.size(), true);
  std::vector<std::vector<int>> confounded(candidates.size());
  auto mark = [&](const std::vector<int>& cols, const IdentifiabilityAnalysis& a) {
    for (std::size_t c = 0; c < cols.size(); ++c) {
      const auto pos = static_cast<std::size_t>(std::find(candidates.begin(), candidates.end(), cols[c]) - candidates.begin());
      if (!a.identifiable[c]) identifiable[pos] = false;
      for (int o : a.confounded_with[c]) confounded[pos].push_back(cols[static_cast<std::size_t>(o)]);
    }
  };
  Eigen::VectorXd r0;
  {
    const Eigen::MatrixXd J0 = estimator.scaled_jacobian(candidates, prior, nullptr, &r0);
    mark(candidates, analyse_identifiability(J0, id_options));
  }
  result.initial_cost = r0.squaredNorm();
  std::vector<int> free = select(candidates, identifiable);

  LmOptions lm;
  lm.max_iterations = options.max_iterations;
  lm.cost_tolerance = options.cost_tolerance;
  lm.step_tolerance = options.step_tolerance;
  lm.gradient_tolerance = options.gradient_tolerance;

  std::mutex progress_mutex;
  auto reporter = [&](int start, int starts, const char* stage) {
    return [&, start, starts, stage](int iteration, double cost) {
      if (!options.progress) return;
      std::lock_guard<std::mutex> lock(progress_mutex);
      options.progress(FitProgress{start, starts, iteration, cost, stage});
    };
  };

  // Starting points in internal coordinates: the prior, then uniform within +-log(spread) of it (fit_setup.hpp).
  const int starts = std::max(1, options.starts);
  Eigen::VectorXd chosen_start = prior;
  for (const auto& [name, value] : options.also_start_at) {
    const int idx = info.parameter_index(name);
    if (idx < 0) throw FitError("fit: a start value for " + name + ": the model has no parameter " + name);
    chosen_start[idx] = value;
  }
  const std::vector<Eigen::VectorXd> start_points = estimation::start_points(
      estimator.internal(free, prior), free, transforms, options,
      options.also_start_at.empty() ? std::nullopt : std::optional<Eigen::VectorXd>(estimator.internal(free, chosen_start)));
  const ResidualFunction weighted = estimator.function(free, ResidualKind::Weighted);
  LmOptions search_lm = lm;
  search_lm.cost_tolerance = std::max(lm.cost_tolerance, options.search_cost_tolerance);
  // The multi-start search: on the FRF data itself, or on FRFs estimated from time records (spectral_companion.hpp).
  std::optional<estimation::SpectralCompanion> companion;
  if (problem.has_time() && options.spectral_search && starts > 1) companion = estimation::spectral_companion(info, data);
  std::optional<OutputErrorProblem> companion_problem;
  std::optional<Estimator> companion_estimator;
  if (companion) {
    FrfWeighting w = options.frf_weighting;
    w.averages = std::max(w.averages, companion->averages);
    companion_problem.emplace(model, companion->data, w);
    companion_estimator.emplace(*companion_problem, prior, transforms);
  }
  const Estimator& searcher = companion ? *companion_estimator : estimator;
  const bool log_search = options.log_search && (companion || (problem.has_frf() && !problem.has_time()));
  const ResidualFunction search_weighted = searcher.function(free, ResidualKind::Weighted);
  const ResidualFunction log_ratio = searcher.function(free, ResidualKind::LogRatio);
  const std::vector<LmResult> runs = estimation::run_starts(starts, options.threads, [&](int s) {
    Eigen::VectorXd theta = start_points[static_cast<std::size_t>(s)];
    if (log_search) theta = estimation::levenberg_marquardt(log_ratio, theta, search_lm, reporter(s, starts, "search")).x;
    return estimation::levenberg_marquardt(search_weighted, theta, lm, reporter(s, starts, "refine"));
  });
  for (const auto& run : runs) result.start_costs.push_back(run.cost);
  result.best_start = estimation::best_start(runs);
  LmResult best = runs[static_cast<std::size_t>(result.best_start)];
  if (companion) {
    // The best spectral start refined on the records; and the prior too, so that an H1 too coarse to lead the
    // search (a short record) never leaves the result worse than a plain fit from the prior. The lower
    // time-domain cost wins (the spectral start on a tie).
    const std::vector<Eigen::VectorXd> refine_from = {best.x, start_points.front()};
    const std::vector<LmResult> refined = estimation::run_starts(2, options.threads, [&](int s) {
      return estimation::levenberg_marquardt(weighted, refine_from[static_cast<std::size_t>(s)], lm,
                                             reporter(s == 0 ? result.best_start : 0, starts, "refine records"));
    });
    const int winner = estimation::best_start(refined);
    best = refined[static_cast<std::size_t>(winner)];
    if (winner == 1) result.best_start = 0;
  }
  if (!std::isfinite(best.cost)) throw FitError("fit: the model cannot be evaluated at any starting point");
  result.cost_history = best.history;
  Eigen::VectorXd values = estimator.full_values(free, best.x);

  // Identifiability at the estimate: rank can be lost away from the prior. Fix what is lost, refit.
  for (;;) {
    if (free.empty()) break;
    const IdentifiabilityAnalysis a = analyse_identifiability(estimator.scaled_jacobian(free, values, nullptr), id_options);
    if (a.rank() == static_cast<int>(free.size())) break;
    mark(free, a);
    const std::vector<int> kept = select(free, a.identifiable);
    for (std::size_t j = 0; j < free.size(); ++j)
      if (!a.identifiable[j]) values[free[j]] = prior[free[j]];
    free = kept;
    best = estimation::levenberg_marquardt(estimator.function(free, ResidualKind::Weighted),
                                           estimator.internal(free, values), lm, reporter(0, 1, "final"));
    result.cost_history.insert(result.cost_history.end(), best.history.begin(), best.history.end());
    values = estimator.full_values(free, best.x);
  }
  result.iterations = best.iterations;
  result.converged = best.converged;
  result.stop_reason = best.stop_reason;

  // Uncertainty from the linearisation at the estimate: cov = s^2 (J^T J)^-1, s^2 = RSS / (n - k).
  Eigen::VectorXd r;
  Eigen::VectorXd scale;
  Eigen::MatrixXd Js = estimator.scaled_jacobian(free, values, &scale, &r);
  const double n = double(problem.residual_count());
  const double k = double(free.size());
  result.cost = r.squaredNorm();
  result.residual_variance = n > k ? result.cost / (n - k) : std::numeric_limits<double>::quiet_NaN();
  result.nrmse = problem.measured_sum_squares() > 0 ? std::sqrt(result.cost / problem.measured_sum_squares())
                                                    : std::numeric_limits<double>::quiet_NaN();
  result.bic = n * std::log(std::max(result.cost, std::numeric_limits<double>::min()) / n) + k * std::log(n);
  auto covariance_of = [&](const Eigen::MatrixXd& J, const Eigen::VectorXd& column_scale) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinV);
    const Eigen::VectorXd s = svd.singularValues();
    Eigen::VectorXd inv2 = Eigen::VectorXd::Zero(s.size());
    for (Eigen::Index i = 0; i < s.size(); ++i)
      if (s[i] > s[0] * 1e-14) inv2[i] = 1 / (s[i] * s[i]);
    const Eigen::MatrixXd cov_scaled = svd.matrixV() * inv2.asDiagonal() * svd.matrixV().transpose();
    return Eigen::MatrixXd(result.residual_variance * column_scale.asDiagonal() * cov_scaled *
                           column_scale.asDiagonal());
  };
  const Eigen::MatrixXd J_free = Js;  // of every fitted parameter at the estimate: their pulls (below)
  // Parameters the optimum pressed against a bound (bound_reached, parameterization.hpp): reported at the bound,
  // without a std, and held there for the others' covariance.
  std::map<int, std::string> at_bound;
  if (!free.empty()) {
    const Eigen::VectorXd sd = covariance_of(Js, scale).diagonal().cwiseMax(0).cwiseSqrt();
    for (std::size_t j = 0; j < free.size(); ++j) {
      const int i = free[j];
      const ParameterTransform& t = transforms[static_cast<std::size_t>(i)];
      const std::string side = bound_reached(t, values[i], sd[static_cast<Eigen::Index>(j)]);
      if (side.empty()) continue;
      at_bound[i] = side;
      values[i] = side == "lower" ? t.lower : t.upper;
    }
  }
  std::vector<int> interior;
  for (int i : free)
    if (!at_bound.count(i)) interior.push_back(i);
  if (interior.size() != free.size() && !interior.empty()) Js = estimator.scaled_jacobian(interior, values, &scale);
  result.values = values;
  for (int i : interior) result.estimated.push_back(info.parameters[static_cast<std::size_t>(i)].name);
  if (!interior.empty()) {
    result.covariance = covariance_of(Js, scale);
    const Eigen::VectorXd sd = result.covariance.diagonal().cwiseMax(0).cwiseSqrt();
    result.correlation = result.covariance.cwiseQuotient(sd * sd.transpose());
  }
  {
    if (!candidates.empty())
      result.singular_values =
          analyse_identifiability(estimator.scaled_jacobian(candidates, values, nullptr), id_options).singular_values;
  }

  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const int i = candidates[c];
    const ParameterInfo& pi = info.parameters[static_cast<std::size_t>(i)];
    ParameterEstimate e;
    e.name = pi.name;
    e.unit = pi.unit;
    e.prior = prior[i];
    e.value = values[i];
    e.estimated = identifiable[c];
    e.identifiable = identifiable[c] && !at_bound.count(i);
    if (at_bound.count(i)) e.at_bound = at_bound[i];
    if (const auto it = std::find(interior.begin(), interior.end(), i); it != interior.end()) {
      const Eigen::Index j = it - interior.begin();
      e.std = std::sqrt(std::max(result.covariance(j, j), 0.0));
    }
    if (const auto it = std::find(free.begin(), free.end(), i); it != free.end()) {
      const Eigen::Index j = it - free.begin();
      // The one-parameter Newton step from the estimate: cost C = |r|^2 drops by (r . J_j)^2 / |J_j|^2 moving
      // along column j of the Jacobian (physical units: Js's columns are J's times the scale, which cancels).
      // Parameters at a bound included: there the pull is what holds them.
      const double along = r.dot(J_free.col(j)), norm2 = J_free.col(j).squaredNorm();
      if (norm2 > 0 && result.residual_variance > 0) {
        e.pull_chi2 = along * along / (norm2 * result.residual_variance);
        // r is model minus measured: the cost falls for a step -along/norm2 in the scaled parameter.
        e.toward = along > 0 ? -1 : along < 0 ? 1 : 0;
      }
    }
    std::vector<int> conf = confounded[c];
    std::sort(conf.begin(), conf.end());
    conf.erase(std::unique(conf.begin(), conf.end()), conf.end());
    for (int o : conf) e.confounded_with.push_back(info.parameters[static_cast<std::size_t>(o)].name);
    result.parameters.push_back(e);
  }

  ModelMatrices m;
  model.evaluate(values, m);
  try {
    result.modes = modal_analysis(m.M, m.C, m.K);
  } catch (const std::exception&) {
    result.modes.clear();  // e.g. a singular mass matrix: no modes to report
  }
  return result;
}

Prediction predict(const Model& model, const std::vector<DataSet>& data, const Eigen::VectorXd& values) {
  const OutputErrorProblem problem(model, data, FrfWeighting{});
  return problem.predict(values);
}

}  // namespace mbgen
