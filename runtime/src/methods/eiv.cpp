// fit_eiv: errors in variables from time records (docs/methods.md#eiv; the cost in eiv_problem.hpp).
#include "mbgen/methods/eiv.hpp"

#include "estimation/fit_setup.hpp"
#include "mbgen/estimation/parameterization.hpp"
#include "numerics/levenberg_marquardt.hpp"
#include "eiv_problem.hpp"
#include "method_result.hpp"

#include <Eigen/SVD>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mbgen {

namespace {

using methods::EivNoise;
using methods::EivProblem;

// The noise levels' largest relative change (in standard deviation) between two estimates.
double noise_change(const std::vector<EivNoise>& a, const std::vector<EivNoise>& b) {
  double change = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto rel = [](const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
      return (x.cwiseSqrt() - y.cwiseSqrt()).cwiseAbs().cwiseQuotient(y.cwiseSqrt()).maxCoeff();
    };
    change = std::max({change, rel(a[i].output, b[i].output), rel(a[i].input, b[i].input)});
  }
  return change;
}

// (J^T J)^-1 by SVD, singular values below 1e-14 of the largest ignored (as the output-error fit's).
Eigen::MatrixXd inverse_normal(const Eigen::MatrixXd& J) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  Eigen::VectorXd inv2 = Eigen::VectorXd::Zero(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i)
    if (s[i] > s[0] * 1e-14) inv2[i] = 1 / (s[i] * s[i]);
  return svd.matrixV() * inv2.asDiagonal() * svd.matrixV().transpose();
}

nlohmann::json noise_json(const Model& model, const std::vector<DataSet>& data, const EivProblem& problem,
                          const std::vector<EivNoise>& noise, const std::vector<double>& input_power) {
  nlohmann::json out = nlohmann::json::array();
  const ModelInfo& info = model.info();
  for (std::size_t r = 0; r < noise.size(); ++r) {
    nlohmann::json j;
    j["data"] = data[r].file();
    j["lines"] = problem.lines(r);
    for (Eigen::Index o = 0; o < noise[r].output.size(); ++o)
      j["output_sigma"][problem.output_names(r)[static_cast<std::size_t>(o)]] = std::sqrt(noise[r].output[o]);
    for (Eigen::Index i = 0; i < noise[r].input.size(); ++i) {
      const std::string& name = info.inputs[static_cast<std::size_t>(i)];
      j["input_sigma"][name] = std::sqrt(noise[r].input[i]);
      j["input_snr_db"][name] = 10 * std::log10(input_power[r * info.inputs.size() + static_cast<std::size_t>(i)] /
                                                noise[r].input[i]);
    }
    out.push_back(j);
  }
  return out;
}

}  // namespace

FitResult fit_eiv(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  const ModelInfo& info = model.info();
  if (data.empty()) throw FitError("fit: no data sets given");
  // Refusals first (FRFs, a record without its force, one too short), before the output-error fit's search runs.
  const estimation::FitSetup setup = estimation::prepare_fit(model, data, options);
  if (setup.candidates.empty()) throw FitError("fit: --method eiv: the model has no parameter to estimate");
  { const EivProblem check(model, data, setup.candidates, setup.prior); }

  // The start: output error's estimate, which settles identifiability and bounds (errors in variables changes the
  // weighting, not what the data determine).
  const FitResult start = fit(model, data, options);
  FitResult result = start;  // its members beside the finisher's (seed, starts, warnings) are output error's
  std::vector<int> free;
  for (const std::string& name : start.estimated) free.push_back(info.parameter_index(name));
  if (free.empty()) throw FitError("fit: --method eiv: output error left no parameter interior and identifiable");

  const EivProblem problem(model, data, free, start.values);
  Eigen::VectorXd values = start.values;
  std::vector<EivNoise> noise = problem.initial_noise();
  for (int i = 0; i < 3; ++i) noise = problem.estimate_noise(values, noise);

  estimation::LmOptions lm;
  lm.max_iterations = options.max_iterations;
  lm.cost_tolerance = options.cost_tolerance;
  lm.step_tolerance = options.step_tolerance;
  lm.gradient_tolerance = options.gradient_tolerance;
  const estimation::ResidualFunction f = [&](const Eigen::VectorXd& theta, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
    const Eigen::VectorXd full = estimation::physical_values(values, free, setup.transforms, theta);
    if (!problem.evaluate(full, noise, r, J)) return false;
    if (J)
      for (std::size_t j = 0; j < free.size(); ++j)
        J->col(static_cast<Eigen::Index>(j)) *= setup.transforms[static_cast<std::size_t>(free[j])].derivative(
            theta[static_cast<Eigen::Index>(j)]);
    return true;
  };
  // The parameters at fixed noise levels, then the levels at the new parameters, until the levels settle.
  estimation::LmResult run;
  int rounds = 0;
  double change = 0;
  for (; rounds < 8; ++rounds) {
    run = estimation::levenberg_marquardt(f, estimation::internal_values(free, setup.transforms, values), lm);
    if (!std::isfinite(run.cost)) throw FitError("fit --method eiv: the model cannot be evaluated from the start");
    values = estimation::physical_values(values, free, setup.transforms, run.x);
    const std::vector<EivNoise> next = problem.estimate_noise(values, noise);
    change = noise_change(next, noise);
    noise = next;
    if (change < 1e-3) break;
  }
  rounds = std::min(rounds + 1, 8);

  // Covariance: s^2 (J^T J)^-1 of the whitened residuals at the estimate, s^2 from the degrees of freedom left
  // after the eliminated unknowns (true force per line, transients) and the parameters.
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  if (!problem.evaluate(values, noise, r, &J)) throw FitError("fit --method eiv: the model cannot be evaluated at the estimate");
  const double dof = double(problem.residual_count() - problem.nuisance_count()) - double(free.size());
  const double cost = r.squaredNorm(), s2 = cost / dof;
  Eigen::VectorXd scale(static_cast<Eigen::Index>(free.size()));
  for (std::size_t j = 0; j < free.size(); ++j) {
    const double v = std::abs(values[free[j]]);
    scale[static_cast<Eigen::Index>(j)] = v > 0 ? v : 1.0;
  }
  const Eigen::MatrixXd cov =
      s2 * scale.asDiagonal() * inverse_normal(J * scale.asDiagonal()) * scale.asDiagonal();

  // The output-error fit's verdicts stand (identifiable, at a bound, confounded, the pull of one held at a bound);
  // an interior optimum has no pull.
  methods::MethodOutcome outcome;
  outcome.method = "eiv";
  outcome.prior = start.prior_values;
  outcome.values = values;
  for (const ParameterEstimate& e : start.parameters) {
    methods::ReportedParameter p{info.parameter_index(e.name), e};
    if (std::find(free.begin(), free.end(), p.index) != free.end()) {
      p.verdicts.pull_chi2 = 0;
      p.verdicts.toward = 0;
    }
    outcome.parameters.push_back(p);
  }
  outcome.estimated = start.estimated;
  outcome.covariance = cov;
  outcome.std_from_covariance = true;
  outcome.scored = setup.candidates;
  outcome.fitted = static_cast<int>(std::count_if(start.parameters.begin(), start.parameters.end(),
                                                  [](const ParameterEstimate& e) { return e.estimated; }));
  methods::finish_result(model, data, options, outcome, result);
  result.iterations = run.iterations;
  result.converged = run.converged && change < 1e-3;
  result.stop_reason = change < 1e-3 ? run.stop_reason
                                     : "the noise levels still changed by " + std::to_string(change) + " after 8 rounds";
  result.cost_history = run.history;

  std::vector<double> input_power;
  for (std::size_t ri = 0; ri < data.size(); ++ri) {
    const TimeRecord& t = std::get<TimeRecord>(data[ri].content);
    for (const std::string& name : info.inputs) {
      const Eigen::VectorXd& u = t.at(name).values;
      input_power.push_back((u.array() - u.mean()).square().mean());
    }
  }
  nlohmann::json j;
  j["noise"] = noise_json(model, data, problem, noise, input_power);
  j["eiv_cost"] = cost;
  j["residual_variance"] = s2;  // about 1/2 when the noise model holds (each real part of a whitened line)
  j["degrees_of_freedom"] = dof;
  j["rounds"] = rounds;
  j["output_error_estimate"] = nlohmann::json::object();
  j["output_error_std"] = nlohmann::json::object();
  for (const ParameterEstimate& e : start.parameters) {
    j["output_error_estimate"][e.name] = e.value;
    if (std::find(start.estimated.begin(), start.estimated.end(), e.name) != start.estimated.end())
      j["output_error_std"][e.name] = e.std;
  }
  // The bounds transforms keep the estimate inside; one pressed onto a bound has no meaningful std (as in output
  // error), which the summary says rather than hides.
  std::vector<std::string> pressed;
  for (std::size_t jj = 0; jj < free.size(); ++jj) {
    const int i = free[jj];
    const auto col = static_cast<Eigen::Index>(jj);
    const double sd = std::sqrt(std::max(cov(col, col), 0.0));
    if (!bound_reached(setup.transforms[static_cast<std::size_t>(i)], values[i], sd).empty())
      pressed.push_back(info.parameters[static_cast<std::size_t>(i)].name);
  }
  j["at_bound"] = pressed;
  std::string summary = "errors in variables (white force and output noise, levels from the data):";
  const nlohmann::json& n0 = j["noise"][0];
  for (const auto& [name, snr] : n0["input_snr_db"].items()) {
    char text[96];
    std::snprintf(text, sizeof text, " force %s noise %.3g (%.1f dB)", name.c_str(),
                  n0["input_sigma"][name].get<double>(), snr.get<double>());
    summary += text;
  }
  if (data.size() > 1) summary += " in " + data[0].file() + " (the others in method_details.eiv.noise)";
  summary += "; started from the output-error estimate";
  for (const std::string& name : pressed) summary += "; " + name + " ended at a bound: its std means nothing";
  j["summary"] = summary;
  result.method_details["eiv"] = j.dump();
  return result;
}

}  // namespace mbgen
