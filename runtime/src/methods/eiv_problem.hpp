// The errors-in-variables problem of `fit --method eiv` (docs/methods.md#eiv). Internal header.
//
// Each time record is taken whole into the frequency domain (DFT with 1/sqrt(N), lines 1 .. ceil(N/2) - 1). The
// model discretised exactly for the record's hold (state_space.hpp) satisfies, line by line and without leakage,
//
//     Y_k = G(z_k) U0_k + z_k C (z_k I - Phi)^-1 t,    G(z) = C (z I - Phi)^-1 (Gamma0 + z Gamma1) + D,
//
// with U0 the true (unmeasured) force and t one real state-sized vector per record (the difference between the
// record's initial and final state: the DFT's "transient" term). The measured U = U0 + NU and Y carry white noise
// of variances sigma_u^2 (per input) and sigma_y^2 (per output), independent of each other. The negative
// log-likelihood (variances given) is, per line,
//
//     min over U0 of  sum_o |Y_o - G_o U0 - T_o|^2 / sigma_y,o^2 + sum_i |U_i - U0_i|^2 / sigma_u,i^2
//       = e^H (Sy + G Su G^H)^-1 e,   e = Y - G U - T,
//
// the Schoukens-Pintelon errors-in-variables cost with G(theta) in its weighting. The residuals here are the
// whitened ones of the left form with U0 (per line) and t (per record) at their least-squares values: the problem
// is linear in them, so they are eliminated (variable projection) and the Jacobian with respect to the physical
// parameters is Kaufman's (the columns projected off the eliminated unknowns' columns; it gives the exact
// gradient and the Gauss-Newton Hessian of the projected cost).
#pragma once

#include "mbgen/estimation/fit.hpp"

#include <Eigen/Core>

#include <complex>
#include <string>
#include <utility>
#include <vector>

namespace mbgen::methods {

// The noise of one record: the variance of one DFT line (with the 1/sqrt(N) normalisation: the per-sample variance
// of white noise) of each of the record's outputs (EivProblem::output_names order) and of each model input.
struct EivNoise {
  Eigen::VectorXd output;
  Eigen::VectorXd input;
};

class EivProblem {
 public:
  // `free`: model indices of the parameters the Jacobian is taken with respect to; `values` (all parameters) fixes
  // the excited block's size. Throws FitError / DataError for FRF data, a record without a model input or output,
  // or one too short for the unknowns.
  EivProblem(const Model& model, const std::vector<DataSet>& data, std::vector<int> free, const Eigen::VectorXd& values);

  // Whitened residuals at the full parameter vector `values` (each record's `# set` values over it), and the
  // Jacobian with respect to the free parameters (physical units) when J is non-null. False where the model cannot
  // be evaluated (singular mass matrix, a pole on a line).
  bool evaluate(const Eigen::VectorXd& values, const std::vector<EivNoise>& noise, Eigen::VectorXd& r,
                Eigen::MatrixXd* J) const;

  // The noise variances by maximum likelihood from the equation errors e = Y - G U - T at `values` (t eliminated
  // with the weights `noise`): |e_o|^2 is exponential with mean sigma_y,o^2 + sum_i |G_oi|^2 sigma_u,i^2, whose
  // three or so constants are fitted over all lines of the record (Fisher scoring). A level below 1e-10 of the
  // signal's power (100 dB) is held there.
  std::vector<EivNoise> estimate_noise(const Eigen::VectorXd& values, const std::vector<EivNoise>& noise) const;

  // A start for estimate_noise: 1e-4 of each output's and 1e-6 of each input's mean line power.
  std::vector<EivNoise> initial_noise() const;

  Eigen::Index residual_count() const { return rows_; }
  // Real unknowns eliminated: 2 per input and line (the true force) and the transient vectors.
  Eigen::Index nuisance_count() const { return nuisance_; }
  std::size_t records() const { return records_.size(); }
  const std::vector<std::string>& output_names(std::size_t record) const { return records_[record].output_names; }
  Eigen::Index lines(std::size_t record) const { return records_[record].U.rows(); }

 private:
  struct Record {
    std::string file;
    std::vector<std::pair<int, double>> overrides;
    std::vector<int> outputs;  // model output indices present in the record
    std::vector<std::string> output_names;
    double dt = 0;
    HoldMode hold = HoldMode::ZeroOrder;
    Eigen::VectorXcd z;  // e^{i 2 pi k / N} per line
    Eigen::MatrixXcd U;  // lines x model inputs
    Eigen::MatrixXcd Y;  // lines x outputs
    Eigen::Index offset = 0, states = 0;
  };
  struct Lines;  // eiv_problem.cpp: one record's per-line model and eliminated unknowns

  Lines solve_lines(const Record& rec, const Eigen::VectorXd& values, const EivNoise& noise, bool derivatives) const;

  const Model& model_;
  std::vector<int> free_;
  std::vector<int> inputs_;
  std::vector<Record> records_;
  Eigen::Index rows_ = 0, nuisance_ = 0;
};

}  // namespace mbgen::methods
