// The output-error least-squares problem over several data sets. Internal header.
//
// Residual layout: data sets in order; an FRF data set contributes, per frequency, per channel in file order, the
// real and the imaginary part, each divided by its standard deviation (FrfWeighting; one line's rows adjacent, so
// that the Jacobian is written and read a line at a time);
// a time record contributes, per model output present in the record (model output order), all samples
// divided by that output's measured RMS.
#pragma once

#include "mbgen/data/data_settings.hpp"
#include "mbgen/estimation/fit.hpp"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace mbgen::estimation {

enum class ResidualKind {
  Weighted,  // the statistically weighted output error
  LogRatio,  // FRF only: log(H_model / H_measured) * |H_measured| / sigma, real and imaginary part (global search)
};

class OutputErrorProblem {
 public:
  // `free_params`: model indices of the parameters the Jacobian is taken with respect to.
  OutputErrorProblem(const Model& model, const std::vector<DataSet>& data, const FrfWeighting& weighting);

  // Residuals at the full parameter vector `values` (per-data-set `# set` values are applied on top), and
  // the Jacobian with respect to the model parameters `free_params` (physical units) when J is non-null.
  // Throws FitError (or DynamicsError) when the model cannot be evaluated.
  // `column_scale` (one per free parameter), when given, multiplies the Jacobian's columns (an optimiser's chain
  // rule to its internal coordinates, applied while the Jacobian is written instead of in another pass over it).
  void evaluate(const Eigen::VectorXd& values, const std::vector<int>& free_params, ResidualKind kind,
                Eigen::VectorXd& r, Eigen::MatrixXd* J, const Eigen::VectorXd* column_scale = nullptr) const;

  Eigen::Index residual_count() const { return count_; }
  double measured_sum_squares() const { return measured_ss_; }
  bool has_frf() const;
  bool has_time() const;
  Prediction predict(const Eigen::VectorXd& values) const;

  // What the cost would be if only the measurement noise remained: sum over the FRF lines of (the noise's standard
  // deviation, frf_noise.hpp, estimated from `data`, the data sets this problem was made of) / (the residual's
  // weighting sigma), squared. NaN with time records (output_error_noise.cpp).
  double expected_noise_cost(const std::vector<DataSet>& data) const;

 private:
  struct Prepared {
    bool frf = false;
    std::vector<std::pair<int, double>> overrides;  // (parameter index, value) from `# set`
    // FRF: the model inputs and outputs the channels use; channel c is entry (channel_output[c],
    // channel_input[c]) of the FRF matrix of those.
    std::vector<double> f_hz;
    std::vector<int> inputs, frf_outputs;
    std::vector<int> channel_output, channel_input;
    std::vector<Eigen::VectorXcd> measured;
    std::vector<Eigen::VectorXd> sigma;  // per real component
    // For the log-ratio residuals, per channel and frequency: 1 / H_measured and the weight |H_measured| / sigma.
    std::vector<Eigen::VectorXcd> inverse_measured;
    std::vector<Eigen::VectorXd> log_weight;
    // time
    Eigen::MatrixXd u;
    double dt = 0;
    HoldMode hold = HoldMode::ZeroOrder;
    std::vector<int> outputs;
    std::vector<Eigen::VectorXd> measured_y;
    std::vector<double> weight;
    std::vector<std::string> names;
    Eigen::Index offset = 0, size = 0;
  };
  const Model& model_;
  std::vector<Prepared> sets_;
  Eigen::Index count_ = 0;
  double measured_ss_ = 0;
};

}  // namespace mbgen::estimation
