// A random mbgen::Model whose every matrix depends on some parameter: for the derivative code paths of all seven
// matrices. Header-only; include from *_test.cpp files only.
#pragma once

#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace mbgen::test {

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
