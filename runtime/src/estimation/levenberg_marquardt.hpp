// Levenberg-Marquardt for small dense least-squares problems. Internal header.
//
// Minimises ||r(x)||^2. Each iteration factors J = Q R once; a trial step for damping lambda solves
// [R; sqrt(lambda) D] dx = [-Q^T r; 0] (D = Marquardt's column scaling, the column norms of J, kept monotone),
// so a rejected trial costs only a small k x k problem. lambda is updated by Nielsen's rule: after a successful
// step by max(1/3, 1 - (2 rho - 1)^3), rho = actual / predicted decrease (a step the linear model predicted well
// lets lambda shrink, a poor one keeps or raises it), after a failed trial by 2, 4, 8, ... (H. B. Nielsen,
// "Damping parameter in Marquardt's method", IMM-REP-1999-05). The former fixed factors (1/3, 10) made long
// cycles of failed trials in the curved valleys of lightly damped FRF fits.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace mbgen::estimation {

// Evaluates r(x) and, when J is non-null, the Jacobian. Returns false when x is not admissible (the model
// cannot be evaluated there); the step is then treated as a failed trial.
using ResidualFunction = std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd* J)>;

struct LmOptions {
  int max_iterations = 200;
  double cost_tolerance = 1e-10;
  double step_tolerance = 1e-10;
  double gradient_tolerance = 1e-12;
};

struct LmResult {
  Eigen::VectorXd x;
  double cost = 0;  // ||r||^2
  int iterations = 0;
  std::vector<double> history;  // cost after each accepted step, starting with the initial cost
  bool converged = false;
  std::string stop_reason;
};

LmResult levenberg_marquardt(const ResidualFunction& f, const Eigen::VectorXd& x0, const LmOptions& options,
                             const std::function<void(int iteration, double cost)>& on_iteration = {});

}  // namespace mbgen::estimation
