// fit_direct: the equations of motion solved for the parameters (docs/methods.md#direct). The data side is in
// direct_equations.cpp, the least squares in direct_solve.cpp; here the iteration (re-weighting at the estimate,
// Gauss-Newton when the matrices are not linear in the parameters), bounds, and the result.
#include "mbgen/methods/direct.hpp"

#include "direct_equations.hpp"
#include "direct_solve.hpp"
#include "method_result.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace mbgen {

namespace {

using methods::DirectEquations;
using methods::DirectSolution;

constexpr int kMaxIterations = 50;
constexpr double kStepTolerance = 1;  // the largest change between two solves, in the units below

// Sum of the derivative entries of M, C, K and B with respect to each candidate, densely, for comparison.
std::vector<Eigen::MatrixXd> derivative_matrices(const Model& model, const Eigen::VectorXd& p,
                                                 const std::vector<int>& candidates) {
  ModelDerivatives d;
  model.derivatives(p, d);
  ModelMatrices m;
  model.evaluate(p, m);
  const Eigen::Index n = m.M.rows(), ni = m.B.cols();
  std::vector<Eigen::MatrixXd> out(candidates.size(), Eigen::MatrixXd::Zero(3 * n, n + ni));
  auto add = [&](const std::vector<DerivativeEntry>& list, Eigen::Index row0, Eigen::Index col0) {
    for (const auto& e : list) {
      const auto it = std::find(candidates.begin(), candidates.end(), e.param);
      if (it != candidates.end()) out[static_cast<std::size_t>(it - candidates.begin())](row0 + e.row, col0 + e.col) += e.value;
    }
  };
  add(d.M, 0, 0);
  add(d.C, n, 0);
  add(d.K, 2 * n, 0);
  add(d.B, 0, n);
  return out;
}

// M, C, K and B are linear (affine) in the candidates when their derivatives are the same at two points.
bool linear_in(const Model& model, const Eigen::VectorXd& prior, const std::vector<int>& candidates) {
  Eigen::VectorXd other = prior;
  for (std::size_t j = 0; j < candidates.size(); ++j) {
    const double v = prior[candidates[j]];
    other[candidates[j]] = v != 0 ? v * (1.1 + 0.05 * double(j)) : 1.0;
  }
  const auto a = derivative_matrices(model, prior, candidates), b = derivative_matrices(model, other, candidates);
  for (std::size_t j = 0; j < a.size(); ++j) {
    const double size = std::max(a[j].cwiseAbs().maxCoeff(), b[j].cwiseAbs().maxCoeff());
    if ((a[j] - b[j]).cwiseAbs().maxCoeff() > 1e-12 * size) return false;
  }
  return true;
}

// The output map gives the coordinates' motion from the data; it cannot depend on what is unknown.
void require_known_output_map(const Model& model, const Eigen::VectorXd& prior, const std::vector<int>& candidates) {
  ModelDerivatives d;
  model.derivatives(prior, d);
  for (const auto* list : {&d.Cd, &d.Cv, &d.Ca})
    for (const auto& e : *list)
      if (e.value != 0 && std::find(candidates.begin(), candidates.end(), e.param) != candidates.end())
        throw FitError("fit: error: --method direct needs an output map that does not depend on the estimated "
                       "parameters, but output " + model.info().outputs[static_cast<std::size_t>(e.row)] +
                       " depends on " + model.info().parameters[static_cast<std::size_t>(e.param)].name);
}

double bound_margin(const ParameterInfo& p, double prior) {
  return 1e-3 * (prior != 0 ? std::abs(prior) : std::isfinite(p.upper - p.lower) ? p.upper - p.lower : 1.0);
}

// One solution of the equations: re-weighted at the estimate until it settles, bounds enforced by holding a
// parameter beyond one at it, parameters the equations cannot determine kept at their prior.
struct Iteration {
  DirectSolution sol;
  Eigen::VectorXd values;
  std::vector<int> free;  // solved for, interior
  std::map<int, std::string> at_bound;
  std::map<int, std::vector<int>> confounded;
  std::vector<int> dropped;
  int iterations = 0;
  bool converged = false;
  double output_error_cost = 0;
};

// `start`: the first reference point (weights, linearisation, instruments); `prior`: where parameters the equations
// cannot determine are kept, and the bounds' margin.
Iteration iterate(const Model& model, const std::vector<DataSet>& data, const DirectEquations& eq,
                  const Eigen::VectorXd& prior, const Eigen::VectorXd& start, const std::vector<int>& candidates,
                  const IdentifiabilityOptions& id_options, bool instrumental) {
  const ModelInfo& info = model.info();
  Iteration it;
  it.free = candidates;
  Eigen::VectorXd reference = start, last = start;
  while (it.iterations < kMaxIterations && !it.free.empty()) {
    ++it.iterations;
    it.sol = methods::solve_direct(model, data, eq, reference, it.free, id_options, instrumental);
    const IdentifiabilityAnalysis& a = it.sol.identifiability;
    if (a.rank() < static_cast<int>(it.free.size())) {
      std::vector<int> kept;
      for (std::size_t j = 0; j < it.free.size(); ++j) {
        for (int o : a.confounded_with[j]) it.confounded[it.free[j]].push_back(it.free[static_cast<std::size_t>(o)]);
        if (a.identifiable[j]) {
          kept.push_back(it.free[j]);
        } else {
          it.dropped.push_back(it.free[j]);
          reference[it.free[j]] = prior[it.free[j]];
        }
      }
      it.free = kept;
      continue;
    }
    // Settled when no parameter moves by more than a thousandth of its standard deviation (or 1e-10 relative,
    // for data without noise).
    double change = 0;
    for (std::size_t j = 0; j < it.free.size(); ++j) {
      const int i = it.free[j];
      const auto jj = static_cast<Eigen::Index>(j);
      const double sd = std::sqrt(std::max(it.sol.covariance(jj, jj), 0.0));
      const double size = std::max({1e-3 * sd, 1e-10 * std::abs(it.sol.values[i]), 1e-300});
      change = std::max(change, std::abs(it.sol.values[i] - last[i]) / size);
    }
    last = it.sol.values;
    // Weights (and, for a nonlinear model, the linearisation) at the new estimate, kept within the bounds.
    for (int i : it.free) {
      const ParameterInfo& p = info.parameters[static_cast<std::size_t>(i)];
      const double margin = bound_margin(p, prior[i]);
      reference[i] = std::min(std::max(it.sol.values[i], p.lower + margin), p.upper - margin);
    }
    if (change > kStepTolerance) continue;
    // Settled: a parameter beyond a bound is held at it and the others solved again.
    int worst = -1;
    double worst_excess = 0;
    for (int i : it.free) {
      const ParameterInfo& p = info.parameters[static_cast<std::size_t>(i)];
      const double excess = std::max(p.lower - it.sol.values[i], it.sol.values[i] - p.upper) / bound_margin(p, prior[i]);
      if (excess > worst_excess) {
        worst = i;
        worst_excess = excess;
      }
    }
    if (worst < 0) {
      it.converged = true;
      break;
    }
    const ParameterInfo& p = info.parameters[static_cast<std::size_t>(worst)];
    it.at_bound[worst] = it.sol.values[worst] < p.lower ? "lower" : "upper";
    reference[worst] = it.at_bound[worst] == "lower" ? p.lower : p.upper;
    it.free.erase(std::find(it.free.begin(), it.free.end(), worst));
  }
  it.values = reference;
  for (int i : it.free) it.values[i] = it.sol.values[i];
  return it;
}

}  // namespace

FitResult fit_direct(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  const ModelInfo& info = model.info();
  const Eigen::VectorXd prior = methods::checked_prior(model, data, options);
  const std::vector<int> candidates = methods::candidate_parameters(info, options);
  if (candidates.empty()) throw FitError("fit: --method direct: the model has no parameter to estimate");
  require_known_output_map(model, prior, candidates);
  const bool linear = linear_in(model, prior, candidates);
  const DirectEquations eq = methods::direct_equations(model, data, prior);
  IdentifiabilityOptions id_options;
  id_options.zero_tolerance = options.zero_tolerance;
  id_options.rank_tolerance = options.rank_tolerance;

  // The instrumental-variable solution is consistent; ordinary least squares is biased by the noise in the
  // regressors and is solved too, for comparison and as a guard: IV is the estimate unless it did not settle or its
  // output-error residual is clearly (by more than half) larger than LS's (a check, not a fit: neither is moved).
  // LS first, from the prior; IV from the LS estimate: instruments from a model within LS's bias of the truth
  // (from a prior 10 % off, the prior model's resonances miss the measured ones, and the instruments, weak there,
  // sent one in ten 40 dB draws of mdof2 astray).
  std::vector<Iteration> runs(2);
  runs[1] = iterate(model, data, eq, prior, prior, candidates, id_options, false);
  runs[0] = iterate(model, data, eq, prior, runs[1].values, candidates, id_options, true);
  for (Iteration& r : runs) r.output_error_cost = methods::output_error_cost(model, data, options, r.values);
  const bool iv_wins = runs[0].sol.instrumental && runs[0].converged &&
                                !(runs[0].output_error_cost > 1.5 * runs[1].output_error_cost);
  Iteration& it = iv_wins ? runs[0] : runs[1];
  const Iteration& other = iv_wins ? runs[1] : runs[0];

  methods::MethodOutcome outcome;
  outcome.method = "direct";
  outcome.prior = prior;
  outcome.values = it.values;
  for (int i : it.free) outcome.estimated.push_back(info.parameters[static_cast<std::size_t>(i)].name);
  if (!it.free.empty()) outcome.covariance = it.sol.covariance;
  for (int i : candidates) {
    methods::ReportedParameter p;
    p.index = i;
    ParameterEstimate& e = p.verdicts;
    e.estimated = std::find(it.dropped.begin(), it.dropped.end(), i) == it.dropped.end();
    e.identifiable = e.estimated && !it.at_bound.count(i);
    if (it.at_bound.count(i)) e.at_bound = it.at_bound[i];
    if (const auto f = std::find(it.free.begin(), it.free.end(), i); f != it.free.end()) {
      const Eigen::Index j = f - it.free.begin();
      e.std = std::sqrt(std::max(outcome.covariance(j, j), 0.0));
    }
    std::vector<int> conf = it.confounded[i];
    std::sort(conf.begin(), conf.end());
    conf.erase(std::unique(conf.begin(), conf.end()), conf.end());
    for (int o : conf) e.confounded_with.push_back(info.parameters[static_cast<std::size_t>(o)].name);
    outcome.parameters.push_back(p);
  }
  outcome.scored = candidates;
  outcome.fitted = static_cast<int>(it.free.size() + it.at_bound.size());
  FitResult result;
  methods::finish_result(model, data, options, outcome, result);
  result.iterations = it.iterations;
  result.converged = it.converged;
  result.stop_reason = it.converged ? (linear ? "solved; the weights at the estimate settled"
                                              : "Gauss-Newton on the equation error converged")
                       : it.free.empty() ? "no parameter left to solve for"
                                         : "iteration limit reached";

  nlohmann::json j;
  j["solver"] = it.sol.instrumental ? "instrumental variables" : "least squares";
  j["linear_in_parameters"] = linear;
  j["iterations"] = it.iterations;
  std::vector<std::string> coordinates;
  for (int c : eq.coordinates) coordinates.push_back(info.coordinates[static_cast<std::size_t>(c)]);
  j["coordinates"] = coordinates;
  j["lines"] = eq.blocks.size();
  j["lines_skipped"] = eq.lines_skipped;
  j["equations"] = it.sol.equations;
  j["equation_error_rms"] = it.sol.equation_rms;
  j["relative_equation_error"] = it.sol.relative_equation_error;
  j["noise_scale"] = it.sol.noise_scale;
  j["condition"] = std::isfinite(it.sol.condition) ? nlohmann::json(it.sol.condition) : nlohmann::json(nullptr);
  nlohmann::json alt = nlohmann::json::object();
  for (const ParameterEstimate& e : result.parameters)
    alt[e.name] = other.values[info.parameter_index(e.name)];
  const double ss = result.nrmse > 0 ? result.cost / (result.nrmse * result.nrmse) : 0;  // the data's weighted norm
  j["other_estimate"] = {{"solver", other.sol.instrumental ? "instrumental variables" : "least squares"},
                         {"values", alt},
                         {"converged", other.converged},
                         {"nrmse", ss > 0 ? std::sqrt(other.output_error_cost / ss) : 0.0}};
  j["notes"] = eq.notes;
  result.method_details["direct"] = j.dump();
  return result;
}

}  // namespace mbgen
