#include "method_setup.hpp"

#include "../estimation/value_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mbgen::methods {

MethodSetup method_setup(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                         const std::string& method) {
  const ModelInfo& info = model.info();
  if (data.empty()) throw FitError("fit: no data sets given");
  for (const DataSet& d : data)
    if (d.is_frf())
      throw FitError(d.file() + ": error: --method " + method +
                     " needs time records (sampled inputs and outputs), but this file holds FRFs");
  MethodSetup s;
  s.prior = info.default_values();
  for (const auto& [name, value] : options.values) {
    const int idx = info.parameter_index(name);
    if (idx < 0) throw FitError("fit: --set " + name + ": the model has no parameter " + name);
    s.prior[idx] = value;
  }
  estimation::check_parameter_values(model, s.prior, options.values.empty() ? "the model's values" : "the values set");
  estimation::check_data_set_values(model, s.prior, data);
  estimation::check_measured_signals(model, data);
  if (options.estimate.empty()) {
    for (std::size_t i = 0; i < info.parameters.size(); ++i)
      if (info.parameters[i].role == ParameterRole::Estimate) s.estimated.push_back(static_cast<int>(i));
  } else {
    for (const auto& name : options.estimate) {
      const int idx = info.parameter_index(name);
      if (idx < 0) throw FitError("fit: the model has no parameter " + name + " (asked to estimate it)");
      s.estimated.push_back(idx);
    }
    std::sort(s.estimated.begin(), s.estimated.end());
    s.estimated.erase(std::unique(s.estimated.begin(), s.estimated.end()), s.estimated.end());
  }
  if (s.estimated.empty()) throw FitError("fit: --method " + method + ": the model has no parameter to estimate");
  s.transforms.resize(info.parameters.size());
  for (int i : s.estimated) {
    try {
      s.transforms[static_cast<std::size_t>(i)] = make_parameter_transform(info.parameters[static_cast<std::size_t>(i)], s.prior[i]);
    } catch (const std::invalid_argument& e) {
      throw FitError(std::string("fit: ") + e.what());
    }
  }
  return s;
}

Eigen::VectorXd values_for(const Model& model, const DataSet& d, const Eigen::VectorXd& values) {
  Eigen::VectorXd v = values;
  for (const auto& [name, value] : d.set()) v[model.info().parameter_index(name)] = value.value;  // checked above
  return v;
}

namespace {

// Output-error residuals at `values` (simulation from rest), each output divided by its measured RMS; and the
// measured signals' weighted sum of squares.
double output_error_cost(const Model& model, const std::vector<DataSet>& data, const Eigen::VectorXd& values,
                         long& count, double& measured_ss) {
  const Prediction p = predict(model, data, values);
  double cost = 0;
  count = 0;
  measured_ss = 0;
  for (std::size_t d = 0; d < data.size(); ++d) {
    const TimeRecord& t = std::get<TimeRecord>(data[d].content);
    for (std::size_t c = 0; c < p.channels[d].size(); ++c) {
      const Eigen::VectorXd& y = t.at(p.channel_names[d][c]).values;
      const double rms = std::sqrt(y.squaredNorm() / double(y.size()));
      const double w = rms > 0 ? 1 / rms : 1.0;
      cost += (p.channels[d][c].real() - y).squaredNorm() * w * w;
      measured_ss += y.squaredNorm() * w * w;
      count += static_cast<long>(y.size());
    }
  }
  return cost;
}

}  // namespace

void fill_common(const Model& model, const std::vector<DataSet>& data, const MethodSetup& setup,
                 const Eigen::VectorXd& values, const std::string& method, FitResult& r) {
  const ModelInfo& info = model.info();
  r.model = info.name;
  r.data.clear();
  for (const auto& d : data) r.data.push_back(d.file());
  r.method = method;
  r.prior_values = setup.prior;
  r.values = values;
  long count = 0;
  double measured_ss = 0;
  r.initial_cost = output_error_cost(model, data, setup.prior, count, measured_ss);
  r.cost = output_error_cost(model, data, values, count, measured_ss);
  r.residual_count = count;
  const double n = double(count), k = double(setup.estimated.size());
  r.residual_variance = n > k ? r.cost / (n - k) : std::numeric_limits<double>::quiet_NaN();
  r.nrmse = measured_ss > 0 ? std::sqrt(r.cost / measured_ss) : std::numeric_limits<double>::quiet_NaN();
  r.bic = n * std::log(std::max(r.cost, std::numeric_limits<double>::min()) / n) + k * std::log(n);
  r.parameters.clear();
  r.estimated.clear();
  for (int i : setup.estimated) {
    const ParameterInfo& pi = info.parameters[static_cast<std::size_t>(i)];
    ParameterEstimate e;
    e.name = pi.name;
    e.unit = pi.unit;
    e.prior = setup.prior[i];
    e.value = values[i];
    e.estimated = true;
    r.parameters.push_back(e);
    r.estimated.push_back(pi.name);
  }
  ModelMatrices m;
  model.evaluate(values, m);
  try {
    r.modes = modal_analysis(m.M, m.C, m.K);
  } catch (const std::exception&) {
    r.modes.clear();  // e.g. a singular mass matrix: no modes to report
  }
}

void set_covariance(const Eigen::MatrixXd& covariance, FitResult& r) {
  r.covariance = covariance;
  const Eigen::VectorXd sd = covariance.diagonal().cwiseMax(0).cwiseSqrt();
  r.correlation = covariance.cwiseQuotient(sd * sd.transpose());
  for (Eigen::Index j = 0; j < sd.size(); ++j)
    for (ParameterEstimate& e : r.parameters)
      if (e.name == r.estimated[static_cast<std::size_t>(j)]) e.std = sd[j];
}

}  // namespace mbgen::methods
