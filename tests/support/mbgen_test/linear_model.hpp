// A hand-written mbgen::Model whose matrices are affine in the parameters, declared entry by entry: for tests of
// the runtime that must not depend on the compiler. Header-only; include from *_test.cpp files only.
#pragma once

#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <limits>
#include <string>
#include <vector>

namespace mbgen::test {

// X(p) = X0 + sum_i p_i X_i for all seven matrices; declared entry by entry.
class LinearModel : public Model {
 public:
  enum Matrix { M, C, K, B, Cd, Cv, Ca };
  LinearModel(std::string name, int n, std::vector<std::string> inputs, std::vector<std::string> outputs) {
    info_.name = std::move(name);
    for (int i = 0; i < n; ++i) info_.coordinates.push_back("q" + std::to_string(i));
    info_.inputs = std::move(inputs);
    info_.outputs = std::move(outputs);
    const auto ni = static_cast<Eigen::Index>(info_.inputs.size()), no = static_cast<Eigen::Index>(info_.outputs.size());
    base_.M = Eigen::MatrixXd::Zero(n, n);
    base_.C = Eigen::MatrixXd::Zero(n, n);
    base_.K = Eigen::MatrixXd::Zero(n, n);
    base_.B = Eigen::MatrixXd::Zero(n, ni);
    base_.Cd = Eigen::MatrixXd::Zero(no, n);
    base_.Cv = Eigen::MatrixXd::Zero(no, n);
    base_.Ca = Eigen::MatrixXd::Zero(no, n);
  }
  int parameter(const std::string& name, double value, ParameterRole role, double lower = 0,
                double upper = std::numeric_limits<double>::infinity(), std::string unit = "") {
    ParameterInfo p;
    p.name = name;
    p.value = value;
    p.role = role;
    p.lower = lower;
    p.upper = upper;
    p.unit = std::move(unit);
    info_.parameters.push_back(p);
    return static_cast<int>(info_.parameters.size()) - 1;
  }
  void set_bounds(int param, double lower, double upper) {
    info_.parameters[static_cast<std::size_t>(param)].lower = lower;
    info_.parameters[static_cast<std::size_t>(param)].upper = upper;
  }
  void constant(Matrix m, int row, int col, double v) { member(base_, m)(row, col) += v; }
  void linear(Matrix m, int param, int row, int col, double coefficient) {
    list(slope_, m).push_back({param, row, col, coefficient});
  }
  // A spring (or damper) of parameter `param` between coordinates i and j (j = -1: ground).
  void element(Matrix m, int param, int i, int j) {
    linear(m, param, i, i, 1);
    if (j >= 0) {
      linear(m, param, j, j, 1);
      linear(m, param, i, j, -1);
      linear(m, param, j, i, -1);
    }
  }

  const ModelInfo& info() const override { return info_; }
  void evaluate(const Eigen::VectorXd& p, ModelMatrices& out) const override {
    out = base_;
    for (int m = M; m <= Ca; ++m)
      for (const auto& e : list(slope_, Matrix(m))) member(out, Matrix(m))(e.row, e.col) += p[e.param] * e.value;
  }
  void derivatives(const Eigen::VectorXd&, ModelDerivatives& out) const override { out = slope_; }

 private:
  static Eigen::MatrixXd& member(ModelMatrices& x, Matrix m) {
    switch (m) {
      case M: return x.M;
      case C: return x.C;
      case K: return x.K;
      case B: return x.B;
      case Cd: return x.Cd;
      case Cv: return x.Cv;
      default: return x.Ca;
    }
  }
  static std::vector<DerivativeEntry>& list(ModelDerivatives& x, Matrix m) {
    switch (m) {
      case M: return x.M;
      case C: return x.C;
      case K: return x.K;
      case B: return x.B;
      case Cd: return x.Cd;
      case Cv: return x.Cv;
      default: return x.Ca;
    }
  }
  static const std::vector<DerivativeEntry>& list(const ModelDerivatives& x, Matrix m) {
    return list(const_cast<ModelDerivatives&>(x), m);
  }
  ModelInfo info_;
  ModelMatrices base_;
  ModelDerivatives slope_;
};

}  // namespace mbgen::test
