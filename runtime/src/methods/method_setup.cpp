#include "method_setup.hpp"

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

}  // namespace mbgen::methods
