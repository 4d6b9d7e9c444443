// Step two of the two-step method: the identified coefficients set against the model's. Internal header.
//
// The compared coefficients are the denominator's a_0 .. a_{q-1} (a_q = 1 on both sides) of each identified
// transfer function and each channel's numerator coefficients that the model has structurally non-zero
// (model_coefficients.hpp). Residual i is the thesis's normalised mismatch (Eq. 3.98) (L_i(p) - L^_i) / |L^_i|,
// L^ identified, L(p) the model's at the data set's parameter values (its `# set` lines applied). With
// use_covariance_weighting() the normalised mismatches are whitened by step one's covariance instead (the Markov
// estimate: the coefficients' correlations, e.g. of a lightly damped pole's a_i, count as they are).
#pragma once

#include "identified_tf.hpp"
#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <complex>
#include <string>
#include <utility>
#include <vector>

namespace mbgen::methods {

// One identified transfer function with what step two needs to set the model against it.
struct StepOneTf {
  std::string file;
  int input = 0;                                  // model input index
  std::vector<int> outputs;                       // model output indices, in the order of tf.outputs
  std::vector<std::pair<int, double>> overrides;  // the data set's `# set` values
  std::vector<std::vector<bool>> pattern;         // structural non-zeros: [0] denominator, [1 + c] numerators
  IdentifiedTf tf;
  // The data show fewer modes than the model has: the model is truncated to the modes nearest these identified ones
  // (model_tf_truncated). Empty: the model's full order.
  std::vector<std::complex<double>> truncated_to;
  double band_lo_hz = 0, band_hi_hz = 0;          // what the data cover
};

struct CoefficientTarget {
  std::size_t tf = 0;
  int channel = -1;  // -1: the denominator
  int power = 0;
  double value = 0;           // identified
  Eigen::Index stacked = 0;   // index into that transfer function's covariance
};

class CoefficientProblem {
 public:
  CoefficientProblem(const Model& model, const std::vector<StepOneTf>& tfs);
  const std::vector<CoefficientTarget>& targets() const { return targets_; }
  // Normalised residuals at the full parameter vector and their Jacobian (physical units) by the model parameters
  // `free` when J is non-null; `model_values` receives the model's coefficients L(p). Throws what the model throws.
  void evaluate(const Eigen::VectorXd& values, const std::vector<int>& free, Eigen::VectorXd& r, Eigen::MatrixXd* J,
                Eigen::VectorXd* model_values = nullptr) const;
  // The covariance of the identified coefficients L^ (targets' order), or an empty matrix when a step one gave none.
  Eigen::MatrixXd identified_covariance() const;
  // Whitens the residuals by the identified covariance; false (nothing changed) when there is none.
  bool use_covariance_weighting();
  // The residuals are W (L(p) - L^): this W.
  Eigen::MatrixXd weight() const;

 private:
  const Model& model_;
  const std::vector<StepOneTf>& tfs_;
  std::vector<CoefficientTarget> targets_;
  Eigen::MatrixXd whitening_;  // applied to the normalised mismatches; empty: none
};

}  // namespace mbgen::methods
