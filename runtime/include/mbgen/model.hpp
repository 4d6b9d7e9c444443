// The numeric model interface of the runtime.
//
// A Model evaluates, at given parameter values, the matrices of
//
//   M q'' + C q' + K q = B u,      y = Cd q + Cv q' + Ca q''
//
// (C includes gyroscopic terms) and their derivatives with respect to every parameter. Two backends serve it:
// generated, compiled code (each emitted model has a `make_model()`), and the in-process evaluator built from
// the compiler's IR (for models changed at run time). This header needs Eigen only.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace mbgen {

enum class ParameterRole { Known, Estimate, Fixed };

struct ParameterInfo {
  std::string name;
  double value = 0;  // default (nominal) value
  ParameterRole role = ParameterRole::Known;
  std::string unit;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

struct ModelInfo {
  std::string name;
  std::vector<ParameterInfo> parameters;  // free parameters, in model order
  std::vector<std::string> coordinates;   // "body.dof"
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;
  int parameter_index(const std::string& n) const {
    for (std::size_t i = 0; i < parameters.size(); ++i)
      if (parameters[i].name == n) return static_cast<int>(i);
    return -1;
  }
  int input_index(const std::string& n) const { return index_of(inputs, n); }
  int output_index(const std::string& n) const { return index_of(outputs, n); }
  Eigen::VectorXd default_values() const {
    Eigen::VectorXd p(static_cast<Eigen::Index>(parameters.size()));
    for (std::size_t i = 0; i < parameters.size(); ++i) p[static_cast<Eigen::Index>(i)] = parameters[i].value;
    return p;
  }

 private:
  static int index_of(const std::vector<std::string>& v, const std::string& n) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (v[i] == n) return static_cast<int>(i);
    return -1;
  }
};

struct ModelMatrices {
  Eigen::MatrixXd M, C, K;   // n x n
  Eigen::MatrixXd B;         // n x inputs
  Eigen::MatrixXd Cd, Cv, Ca;  // outputs x n
};

// One non-zero entry of the derivative of a matrix with respect to parameter `param`.
struct DerivativeEntry {
  int param = 0, row = 0, col = 0;
  double value = 0;
};

struct ModelDerivatives {
  std::vector<DerivativeEntry> M, C, K, B, Cd, Cv, Ca;
};

class Model {
 public:
  virtual ~Model() = default;
  virtual const ModelInfo& info() const = 0;
  // p has info().parameters.size() entries.
  virtual void evaluate(const Eigen::VectorXd& p, ModelMatrices& out) const = 0;
  virtual void derivatives(const Eigen::VectorXd& p, ModelDerivatives& out) const = 0;
};

}  // namespace mbgen
