// Levenberg-Marquardt for small dense least-squares problems. Internal header.
//
// Minimises ||r(x)||^2. Each iteration factors J = Q R once (row_block_qr.hpp: R and Q^T r, never Q; the gradient
// and J's column norms follow from them); a trial step for damping lambda solves
// [R; sqrt(lambda) D] dx = [-Q^T r; 0] (D = Marquardt's column scaling, the column norms of J, kept monotone),
// and a trial step evaluates r alone: the Jacobian is evaluated only at an accepted point, so a rejected trial
// costs one plain evaluation (for a time record, one simulation instead of one per parameter). The damping
// update is LmOptions::damping's.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace mbgen::estimation {

// Evaluates r(x) and, when J is non-null, the Jacobian. Returns false when x is not admissible (the model
// cannot be evaluated there); the step is then treated as a failed trial.
using ResidualFunction = std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd* J)>;

// How lambda changes between trials.
//  - Classic: shrinks by 3 after an accepted step, grows by 10 after a rejected trial.
//  - Nielsen (H. B. Nielsen, "Damping parameter in Marquardt's method", IMM-REP-1999-05): after an accepted step
//    lambda is scaled by max(1/3, 1 - (2 rho - 1)^3), rho the gain ratio (actual over predicted decrease), so a
//    step the linear model predicted well shrinks it by 3 and a poor one keeps it; after a rejected trial it grows
//    by 2, 4, 8, ... . Fewer rejected trials in curved valleys (the spindle's fits: 30 % fewer trials), but the
//    fits then reach other local optima, some worse; no estimator uses it (bench/README.md, "The CI pass").
enum class LmDamping { Classic, Nielsen };

struct LmOptions {
  int max_iterations = 200;
  LmDamping damping = LmDamping::Classic;
  double cost_tolerance = 1e-10;
  double step_tolerance = 1e-10;
  double gradient_tolerance = 1e-12;
  // A fit still descending at max_iterations goes on, while its last `continue_window` accepted steps together
  // lowered n ln(cost) (n residuals: BIC's measure of fit) by more than `continue_gain`, up to `iteration_cap`
  // iterations in all. continue_gain 0: it stops at max_iterations.
  double continue_gain = 0;
  int continue_window = 50;
  int iteration_cap = 0;
  // A fit whose last `stall_window` accepted steps together lowered n ln(cost) by less than `stall_gain` stops,
  // converged (stop_reason kStalled): for a fit that only ranks models by BIC, a crawl that gains a fraction of a
  // unit per window changes no ranking. 0: off.
  double stall_gain = 0;
  int stall_window = 20;
  // Checked before every iteration: true stops the fit where it stands ("abandoned"; a multi-start's later start
  // whose result is no longer wanted, multistart.hpp).
  std::function<bool()> abandoned;
};

// LmResult::stop_reason of a fit stopped by LmOptions::abandoned.
inline constexpr char kAbandoned[] = "abandoned";
// LmResult::stop_reason of a fit stopped by LmOptions::stall_gain.
inline constexpr char kStalled[] = "stalled: the last steps gained too little in n ln(cost)";

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
