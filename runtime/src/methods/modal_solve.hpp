// The modal objectives solved for parameters: a Levenberg-Marquardt fit of mass/stiffness parameters (on a log
// scale) to the reference modes' frequencies, shapes and scales, and the linear least squares of damping parameters
// on the modal damping ratios. Shared by the modal method (modal_fit.cpp), the start from the data's modes
// (modal_start.cpp) and, through their generic forms (log_scale_fit, solve_damping_ratios), the update of a model to
// output-only modes (operational_update.cpp). Internal header.
#pragma once

#include "modal_configurations.hpp"

#include "mbgen/estimation/fit.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace mbgen::methods {

struct LocalOptimum {
  Eigen::VectorXd p;  // all parameters
  double cost = 0;
  bool converged = false;
  int iterations = 0;
};

// The objectives of `modes` at `base` with parameters `which` = exp(x); false outside the bounds or when the model's
// modes cannot be paired.
bool residuals_at(const ModalProblem& pr, const Eigen::VectorXd& base, const std::vector<int>& which,
                  const std::vector<int>& modes, const Eigen::VectorXd& x, Eigen::VectorXd& r);

// Any objectives of the full parameter vector p; false where they cannot be evaluated (the modes cannot be paired).
using ParameterObjectives = std::function<bool(const Eigen::VectorXd& p, Eigen::VectorXd& r)>;

// Levenberg-Marquardt on log(parameters `which`) from `start` (the others at `base`) of objectives `f`, false
// outside the parameters' bounds; Jacobian by forward differences (backward at a bound), with FitOptions' stopping
// rules.
LocalOptimum log_scale_fit(const ModelInfo& info, const ParameterObjectives& f, const Eigen::VectorXd& base,
                           const Eigen::VectorXd& start, const std::vector<int>& which, const FitOptions& options);

// The objectives r and their Jacobian J with respect to log(parameters `which`) at p, as log_scale_fit takes them;
// false where they cannot be evaluated.
bool log_scale_jacobian(const ModelInfo& info, const ParameterObjectives& f, const Eigen::VectorXd& p,
                        const std::vector<int>& which, Eigen::VectorXd& r, Eigen::MatrixXd& J);

// log_scale_fit of the modal objectives of `modes`.
LocalOptimum local_fit(const ModalProblem& pr, const Eigen::VectorXd& base, const Eigen::VectorXd& start,
                       const std::vector<int>& which, const std::vector<int>& modes, const FitOptions& options);

// Which parameters act on M or K (structural), which on C only (damping); the others (acting on the input or
// output map, on both, on none, or structural with a non-positive prior) in `other` with the reason, for the modal
// method's refusals (Ellinger & Zaeh's assumption A1).
struct ParameterClasses {
  std::vector<int> structural, damping;
  std::vector<std::pair<int, std::string>> other;
};
ParameterClasses classify_parameters(const Model& model, const Eigen::VectorXd& prior, const std::vector<int>& candidates);

// The damping parameters `damping` in p by least squares on the modal damping ratios of every reference mode, at
// fixed M and K: zeta_r = zeta_res,r + sum_j q_rj c_j, rows divided by zeta_ref (the NDD); q by differences
// (steps relative to p and `prior`), relinearised `iterations` times, each value clipped to its bounds. Appends
// {relative_step, ndd_residual_norm} per iteration to `log`. Throws FitError when the modes cannot be paired or the
// ratios cannot separate the parameters.
void solve_damping(const ModalProblem& pr, const std::vector<int>& damping, const Eigen::VectorXd& prior,
                   int iterations, Eigen::VectorXd& p, nlohmann::json& log);

// solve_damping's least squares for any reference damping ratios: `ratios` gives the model's ratios of the
// reference modes at p (false: the modes cannot be paired), `zeta_ref` the references' and `row_scale` what each row
// is divided by (solve_damping: zeta_ref; a weighted fit: the ratio's standard deviation). Messages start with
// `what` and name `modes_text`. `weighted_q` (when given) receives the last linearisation's scaled rows Q.
using DampingRatios = std::function<bool(const Eigen::VectorXd& p, Eigen::VectorXd& zeta)>;
void solve_damping_ratios(const ModelInfo& info, const DampingRatios& ratios, const Eigen::VectorXd& zeta_ref,
                          const Eigen::VectorXd& row_scale, const std::vector<int>& damping,
                          const Eigen::VectorXd& prior, int iterations, const std::string& what,
                          const std::string& modes_text, Eigen::VectorXd& p, nlohmann::json& log,
                          Eigen::MatrixXd* weighted_q = nullptr);

}  // namespace mbgen::methods
