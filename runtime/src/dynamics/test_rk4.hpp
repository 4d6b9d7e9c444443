// Test helper: fine fixed-step RK4 integration of M q'' + C q' + K q = B u(t) in second-order form, an independent
// route to check discretisations and simulations against.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

#include <functional>

namespace mbgen::test {

struct SecondOrderRk4 {
  Eigen::MatrixXd M, C, K, B;

  // Integrates from q = q' = 0 over `samples` intervals of length dt with `substeps` RK4 steps each. The input is
  // u(k, a): in sample interval k at fraction a in [0, 1] of it (so that a piecewise-constant input is exactly
  // the value of its sample, with no rounding of t / dt). Returns the states [q; q'] at the sample instants as
  // rows (samples x 2n).
  Eigen::MatrixXd run(const std::function<Eigen::VectorXd(int, double)>& u, int samples, double dt,
                      int substeps) const {
    const Eigen::Index n = M.rows();
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
    auto f = [&](int k, double a, const Eigen::VectorXd& x) {
      Eigen::VectorXd dx(2 * n);
      dx.head(n) = x.tail(n);
      dx.tail(n) = lu.solve(B * u(k, a) - C * x.tail(n) - K * x.head(n));
      return dx;
    };
    Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * n);
    Eigen::MatrixXd states(samples, 2 * n);
    const double h = dt / substeps;
    for (int k = 0; k < samples; ++k) {
      states.row(k) = x.transpose();
      for (int j = 0; j < substeps; ++j) {
        const double a = static_cast<double>(j) / substeps, da = 1.0 / substeps;
        const Eigen::VectorXd k1 = f(k, a, x), k2 = f(k, a + da / 2, x + h / 2 * k1),
                              k3 = f(k, a + da / 2, x + h / 2 * k2), k4 = f(k, a + da, x + h * k3);
        x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      }
    }
    return states;
  }
};

}  // namespace mbgen::test
