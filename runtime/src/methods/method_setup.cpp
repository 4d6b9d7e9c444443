#include "method_setup.hpp"

#include "method_result.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mbgen::methods {

MethodSetup method_setup(const Model& model, const std::vector<DataSet>& data, const FitOptions& options,
                         const std::string& method) {
  if (data.empty()) throw FitError("fit: no data sets given");
  for (const DataSet& d : data)
    if (d.is_frf())
      throw FitError(d.file() + ": error: --method " + method +
                     " needs time records (sampled inputs and outputs), but this file holds FRFs");
  MethodSetup setup = estimation::prepare_fit(model, data, options);
  if (setup.candidates.empty()) throw FitError("fit: --method " + method + ": the model has no parameter to estimate");
  return setup;
}

Eigen::VectorXd values_for(const Model& model, const DataSet& d, const Eigen::VectorXd& values) {
  Eigen::VectorXd v = values;
  for (const auto& [name, value] : d.set()) v[model.info().parameter_index(name)] = value.value;  // checked above
  return v;
}

void fill_common(const Model& model, const std::vector<DataSet>& data, const MethodSetup& setup,
                 const Eigen::VectorXd& values, const std::string& method, FitResult& r) {
  const ModelInfo& info = model.info();
  describe_run(info, data, method, setup.prior, r);
  r.values = values;
  r.parameters.clear();
  r.estimated.clear();
  for (int i : setup.candidates) {
    ParameterEstimate e = parameter_estimate(info, i, setup.prior, values);
    e.estimated = true;
    r.parameters.push_back(e);
    r.estimated.push_back(e.name);
  }
  // The output-error numbers as every method reports them (method_result.hpp): the same residual mbgen::fit
  // minimises, so that the methods compare with it and with each other.
  score_by_output_error(model, data, FitOptions{}, setup.candidates, static_cast<int>(setup.candidates.size()), r);
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
