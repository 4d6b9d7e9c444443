// Test helpers: hand-written mbgen::Model implementations with hand-derived matrices and derivatives, for tests
// of the runtime that must not depend on the compiler. Header-only; include from *_test.cpp files.
#pragma once

#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <random>
#include <vector>

namespace mbgen::test {

// mdof2 (docs/reference-models.md): two masses, coordinates mass1.x and mass2.x, input F1 on mass1, outputs
// d1 = q1 and d2 = q2. Parameters in model order m1, m2, k11, k22, k12, c11, c22, c12 (Table 5.1 defaults).
// With `extra_outputs` two more outputs are appended to exercise the velocity and acceleration paths:
// v1 = q1' and a2 = q2''.
class Mdof2Model : public Model {
 public:
  enum Param { m1, m2, k11, k22, k12, c11, c22, c12, count };

  explicit Mdof2Model(bool extra_outputs = false) : extra_(extra_outputs) {
    info_.name = "mdof2";
    auto add = [&](const char* name, double value, ParameterRole role, const char* unit) {
      ParameterInfo p;
      p.name = name;
      p.value = value;
      p.role = role;
      p.unit = unit;
      p.lower = 0;
      info_.parameters.push_back(p);
    };
    add("m1", 1.39, ParameterRole::Estimate, "kg");
    add("m2", 1.09, ParameterRole::Estimate, "kg");
    add("k11", 1.38e6, ParameterRole::Estimate, "N/m");
    add("k22", 0.24e6, ParameterRole::Estimate, "N/m");
    add("k12", 0.12e6, ParameterRole::Estimate, "N/m");
    add("c11", 13.42, ParameterRole::Estimate, "N s/m");
    add("c22", 0.47, ParameterRole::Estimate, "N s/m");
    add("c12", 0.0, ParameterRole::Fixed, "N s/m");
    info_.coordinates = {"mass1.x", "mass2.x"};
    info_.inputs = {"F1"};
    info_.outputs = {"d1", "d2"};
    if (extra_) {
      info_.outputs.push_back("v1");
      info_.outputs.push_back("a2");
    }
  }

  const ModelInfo& info() const override { return info_; }

  void evaluate(const Eigen::VectorXd& p, ModelMatrices& out) const override {
    out.M.resize(2, 2);
    out.M << p[m1], 0, 0, p[m2];
    out.K.resize(2, 2);
    out.K << p[k11] + p[k12], -p[k12], -p[k12], p[k22] + p[k12];
    out.C.resize(2, 2);
    out.C << p[c11] + p[c12], -p[c12], -p[c12], p[c22] + p[c12];
    out.B.resize(2, 1);
    out.B << 1, 0;
    const Eigen::Index ny = extra_ ? 4 : 2;
    out.Cd = Eigen::MatrixXd::Zero(ny, 2);
    out.Cv = Eigen::MatrixXd::Zero(ny, 2);
    out.Ca = Eigen::MatrixXd::Zero(ny, 2);
    out.Cd(0, 0) = 1;
    out.Cd(1, 1) = 1;
    if (extra_) {
      out.Cv(2, 0) = 1;
      out.Ca(3, 1) = 1;
    }
  }

  void derivatives(const Eigen::VectorXd&, ModelDerivatives& out) const override {
    out = ModelDerivatives{};
    out.M = {{m1, 0, 0, 1}, {m2, 1, 1, 1}};
    out.K = {{k11, 0, 0, 1}, {k12, 0, 0, 1}, {k12, 0, 1, -1}, {k12, 1, 0, -1}, {k12, 1, 1, 1}, {k22, 1, 1, 1}};
    out.C = {{c11, 0, 0, 1}, {c12, 0, 0, 1}, {c12, 0, 1, -1}, {c12, 1, 0, -1}, {c12, 1, 1, 1}, {c22, 1, 1, 1}};
  }

 private:
  ModelInfo info_;
  bool extra_;
};

// A random model whose matrices are affine in the parameters, X(p) = X0 + sum_i p_i X_i, with every X_i sparse
// (a few entries) and every matrix (M, C, K, B, Cd, Cv, Ca) depending on some parameter, so that derivative
// code paths for all seven matrices are exercised. M0 and K0 are symmetric positive definite and C0 is
// positive semi-definite plus a skew (gyroscopic) part; the parameter perturbations are symmetric and small, so
// M stays invertible near the default parameters (all 1).
class RandomAffineModel : public Model {
 public:
  RandomAffineModel(int n, int inputs, int outputs, int parameters, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    auto random = [&](Eigen::Index r, Eigen::Index c) {
      Eigen::MatrixXd X(r, c);
      for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] = uniform(rng);
      return X;
    };
    const Eigen::MatrixXd L = random(n, n);
    base_.M = L * L.transpose() + n * Eigen::MatrixXd::Identity(n, n);
    const Eigen::MatrixXd R = random(n, n);
    base_.K = 1e4 * (R * R.transpose() + n * Eigen::MatrixXd::Identity(n, n));
    const Eigen::MatrixXd S = random(n, n);
    base_.C = 1e-2 * base_.K + 1e-1 * (S - S.transpose());
    base_.B = random(n, inputs);
    base_.Cd = random(outputs, n);
    base_.Cv = 1e-2 * random(outputs, n);
    base_.Ca = 1e-4 * random(outputs, n);

    std::uniform_int_distribution<int> row_n(0, n - 1), row_in(0, inputs - 1), row_out(0, outputs - 1);
    for (int k = 0; k < parameters; ++k) {
      // A symmetric pair (or diagonal entry) in one of M, C, K and one entry in B or an output matrix.
      const int i = row_n(rng), j = row_n(rng);
      const double scale = 0.3 + 0.7 * std::abs(uniform(rng));
      std::vector<DerivativeEntry>* target = nullptr;
      double magnitude = 1;
      switch (k % 3) {
        case 0: target = &slope_.M; magnitude = 0.1 * base_.M.diagonal().minCoeff(); break;
        case 1: target = &slope_.C; magnitude = 0.05 * base_.C.diagonal().maxCoeff(); break;
        default: target = &slope_.K; magnitude = 0.1 * base_.K.diagonal().minCoeff(); break;
      }
      target->push_back({k, i, j, scale * magnitude});
      if (i != j) target->push_back({k, j, i, scale * magnitude});
      switch (k % 4) {
        case 0: slope_.B.push_back({k, row_n(rng), row_in(rng), 0.1 * uniform(rng)}); break;
        case 1: slope_.Cd.push_back({k, row_out(rng), row_n(rng), 0.1 * uniform(rng)}); break;
        case 2: slope_.Cv.push_back({k, row_out(rng), row_n(rng), 1e-3 * uniform(rng)}); break;
        default: slope_.Ca.push_back({k, row_out(rng), row_n(rng), 1e-5 * uniform(rng)}); break;
      }
    }
    info_.name = "random_affine";
    for (int k = 0; k < parameters; ++k) {
      ParameterInfo p;
      p.name = "p" + std::to_string(k);
      p.value = 1.0;
      info_.parameters.push_back(p);
    }
    for (int i = 0; i < n; ++i) info_.coordinates.push_back("q" + std::to_string(i));
    for (int i = 0; i < inputs; ++i) info_.inputs.push_back("u" + std::to_string(i));
    for (int i = 0; i < outputs; ++i) info_.outputs.push_back("y" + std::to_string(i));
  }

  const ModelInfo& info() const override { return info_; }

  void evaluate(const Eigen::VectorXd& p, ModelMatrices& out) const override {
    out = base_;
    auto apply = [&](const std::vector<DerivativeEntry>& entries, Eigen::MatrixXd& X) {
      for (const auto& e : entries) X(e.row, e.col) += p[e.param] * e.value;
    };
    apply(slope_.M, out.M);
    apply(slope_.C, out.C);
    apply(slope_.K, out.K);
    apply(slope_.B, out.B);
    apply(slope_.Cd, out.Cd);
    apply(slope_.Cv, out.Cv);
    apply(slope_.Ca, out.Ca);
  }

  void derivatives(const Eigen::VectorXd&, ModelDerivatives& out) const override { out = slope_; }

 private:
  ModelInfo info_;
  ModelMatrices base_;
  ModelDerivatives slope_;
};

}  // namespace mbgen::test
