#include "fit_setup.hpp"

#include "fit_inputs.hpp"
#include "multistart.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mbgen::estimation {

FitSetup prepare_fit(const Model& model, const std::vector<DataSet>& data, const FitOptions& options) {
  const ModelInfo& info = model.info();
  FitSetup s;
  s.prior = checked_prior(model, data, options);
  s.candidates = candidate_parameters(info, options);
  s.transforms.resize(info.parameters.size());
  for (int i : s.candidates) {
    try {
      s.transforms[static_cast<std::size_t>(i)] =
          make_parameter_transform(info.parameters[static_cast<std::size_t>(i)], s.prior[i]);
    } catch (const std::invalid_argument& e) {
      throw FitError(std::string("fit: ") + e.what());
    }
  }
  return s;
}

Eigen::VectorXd physical_values(const Eigen::VectorXd& base, const std::vector<int>& free,
                                const std::vector<ParameterTransform>& transforms, const Eigen::VectorXd& theta) {
  Eigen::VectorXd full = base;
  for (std::size_t j = 0; j < free.size(); ++j)
    full[free[j]] = transforms[static_cast<std::size_t>(free[j])].to_physical(theta[static_cast<Eigen::Index>(j)]);
  return full;
}

Eigen::VectorXd internal_values(const std::vector<int>& free, const std::vector<ParameterTransform>& transforms,
                                const Eigen::VectorXd& values) {
  Eigen::VectorXd theta(static_cast<Eigen::Index>(free.size()));
  for (std::size_t j = 0; j < free.size(); ++j)
    theta[static_cast<Eigen::Index>(j)] = transforms[static_cast<std::size_t>(free[j])].to_internal(values[free[j]]);
  return theta;
}

std::vector<Eigen::VectorXd> start_points(const Eigen::VectorXd& theta0, const std::vector<int>& free,
                                          const std::vector<ParameterTransform>& transforms, const FitOptions& options,
                                          const std::vector<Eigen::VectorXd>& chosen) {
  const int starts = std::max(1, options.starts);
  std::vector<Eigen::VectorXd> out;
  StartSampler sampler(options.seed);
  const double half_width = std::log(std::max(options.spread, 1.0));
  for (int s = 0; s < starts; ++s) {
    Eigen::VectorXd theta = theta0;
    if (s >= 1 && static_cast<std::size_t>(s) <= chosen.size()) {
      out.push_back(chosen[static_cast<std::size_t>(s - 1)]);
      continue;
    }
    if (s > 0)
      for (std::size_t j = 0; j < free.size(); ++j) {
        const double u = sampler.symmetric_unit();
        const ParameterTransform& t = transforms[static_cast<std::size_t>(free[j])];
        if (t.kind == BoundKind::None)
          theta[static_cast<Eigen::Index>(j)] *= std::exp(half_width * u);  // multiplicative around the prior
        else
          theta[static_cast<Eigen::Index>(j)] += half_width * u;
      }
    out.push_back(theta);
  }
  return out;
}

}  // namespace mbgen::estimation
