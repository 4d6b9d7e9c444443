#include "numerics/levenberg_marquardt.hpp"

#include "numerics/row_block_qr.hpp"

#include <Eigen/QR>

#include <cmath>
#include <limits>

namespace mbgen::estimation {

namespace {

// J = Q R with Q^T r (row_block_qr.hpp), evaluated at x. False where the model cannot be evaluated there or r or J is
// not finite (a non-finite entry of J makes R non-finite: checking R costs k^2 instead of a pass over J).
bool evaluate_and_factor(const ResidualFunction& f, const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd& J,
                         Eigen::MatrixXd& R, Eigen::VectorXd& qtr) {
  if (!f(x, r, &J) || !r.allFinite()) return false;
  row_block_qr(J, r, R, qtr);
  return R.allFinite() && qtr.allFinite();
}

}  // namespace

LmResult levenberg_marquardt(const ResidualFunction& f, const Eigen::VectorXd& x0, const LmOptions& options,
                             const std::function<void(int, double)>& on_iteration) {
  LmResult res;
  res.x = x0;
  const Eigen::Index k = x0.size();
  Eigen::VectorXd r, r_new;
  Eigen::MatrixXd J;  // the Jacobian's buffer: only its factor R is kept
  Eigen::MatrixXd R, R_new;
  Eigen::VectorXd qtr, qtr_new;
  if (!evaluate_and_factor(f, res.x, r, J, R, qtr)) {
    res.cost = std::numeric_limits<double>::infinity();
    res.stop_reason = "the model cannot be evaluated at the starting point";
    return res;
  }
  res.cost = r.squaredNorm();
  res.history.push_back(res.cost);
  if (k == 0) {
    res.converged = true;
    res.stop_reason = "no parameters";
    return res;
  }
  double lambda = 1e-3;
  Eigen::VectorXd D = Eigen::VectorXd::Zero(k);
  // What the last `window` accepted steps together lowered n ln(cost) by; NaN before there were that many.
  const auto window_gain = [&](int window) {
    const std::size_t steps = res.history.size() - 1, w = static_cast<std::size_t>(window);
    return window > 0 && steps >= w ? static_cast<double>(r.size()) * std::log(res.history[steps - w] / res.cost)
                                    : std::numeric_limits<double>::quiet_NaN();
  };
  // Past max_iterations: whether the last continue_window steps gained more than continue_gain.
  const auto still_descending = [&](int it) {
    return options.continue_gain > 0 && it < options.iteration_cap &&
           window_gain(options.continue_window) > options.continue_gain;
  };
  for (int it = 0; it < options.max_iterations || still_descending(it); ++it) {
    if (options.abandoned && options.abandoned()) {
      res.stop_reason = kAbandoned;
      return res;
    }
    // J = Q R: the gradient J^T r = R^T Q^T r and J's column norms are R's.
    const Eigen::VectorXd gradient = R.transpose() * qtr;
    const Eigen::VectorXd col = R.colwise().norm().transpose();
    D = D.cwiseMax(col);
    const double dmax = D.maxCoeff();
    const Eigen::VectorXd Ds = D.cwiseMax(1e-12 * (dmax > 0 ? dmax : 1.0));
    if ((gradient.array().abs() / (Ds.array() * std::sqrt(std::max(res.cost, 1e-300)))).maxCoeff() <
        options.gradient_tolerance) {
      res.converged = true;
      res.stop_reason = "gradient below tolerance";
      break;
    }
    bool accepted = false;
    double growth = options.damping == LmDamping::Nielsen ? 2 : 10;  // lambda's factor after a rejected trial
    while (lambda < 1e16) {
      Eigen::MatrixXd A(k + k, k);
      A.topRows(k) = R;
      A.bottomRows(k) = (std::sqrt(lambda) * Ds).asDiagonal();
      Eigen::VectorXd b = Eigen::VectorXd::Zero(k + k);
      b.head(k) = -qtr;
      const Eigen::VectorXd dx = A.householderQr().solve(b);
      const Eigen::VectorXd x_new = res.x + dx;
      // The trial needs only r; the Jacobian (for a time record, a simulation of every parameter's sensitivity)
      // is evaluated once the step is accepted, so a rejected trial costs one plain evaluation.
      const bool ok = dx.allFinite() && f(x_new, r_new, nullptr) && r_new.allFinite() && r_new.squaredNorm() < res.cost &&
                      evaluate_and_factor(f, x_new, r_new, J, R_new, qtr_new);
      const double cost_new = ok ? r_new.squaredNorm() : std::numeric_limits<double>::infinity();
      if (ok && cost_new < res.cost) {
        const double decrease = (res.cost - cost_new) / res.cost;
        // Gain ratio: the actual decrease over the one the linearised model ||r + J dx||^2 predicts, which is
        // ||Q^T r||^2 - ||Q^T r + R dx||^2 (the part of r outside J's range does not change).
        const double predicted = qtr.squaredNorm() - (qtr + R * dx).squaredNorm();
        const double rho = predicted > 0 ? (res.cost - cost_new) / predicted : 0;
        const double step = (dx.array() * Ds.array()).matrix().norm() / Ds.norm();
        res.x = x_new;
        r.swap(r_new);
        R.swap(R_new);
        qtr.swap(qtr_new);
        res.cost = cost_new;
        res.history.push_back(cost_new);
        ++res.iterations;
        if (on_iteration) on_iteration(res.iterations, cost_new);
        const double shrink = options.damping == LmDamping::Nielsen
                                  ? std::max(1.0 / 3, 1 - std::pow(2 * std::min(rho, 1.0) - 1, 3))
                                  : 1.0 / 3;
        lambda = std::max(lambda * shrink, 1e-15);
        accepted = true;
        if (decrease < options.cost_tolerance) {
          res.converged = true;
          res.stop_reason = "relative cost decrease below tolerance";
        } else if (dx.norm() < options.step_tolerance || step < options.step_tolerance) {
          res.converged = true;
          res.stop_reason = "step below tolerance";
        } else if (options.stall_gain > 0 && window_gain(options.stall_window) < options.stall_gain) {
          res.converged = true;
          res.stop_reason = kStalled;
        }
        break;
      }
      lambda *= growth;
      if (options.damping == LmDamping::Nielsen) growth *= 2;
    }
    if (!accepted) {
      res.converged = true;  // no descent direction left at machine precision: a (local) minimum
      res.stop_reason = "no further decrease possible";
      break;
    }
    if (res.converged) break;
  }
  if (!res.converged && res.stop_reason.empty()) res.stop_reason = "iteration limit reached";
  return res;
}

}  // namespace mbgen::estimation
