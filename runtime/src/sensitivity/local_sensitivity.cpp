// Local sensitivities of the modes by first-order eigenvalue perturbation of the state matrix:
// dlambda = w^T dA v with w^T v = 1 (state_modes normalizes left * right = I), dA from state_space_derivatives.
#include "mbgen/sensitivity/sensitivity.hpp"
#include "mbgen/dynamics/state_modes.hpp"
#include "mbgen/dynamics/state_space.hpp"
#include "numerics/constants.hpp"

#include <cmath>
#include <limits>

namespace mbgen {

using numerics::kTwoPi;

LocalSensitivity local_sensitivity(const Model& model, const Eigen::VectorXd& p) {
  const ModelInfo& info = model.info();
  const int count = static_cast<int>(info.parameters.size());
  ModelMatrices m;
  model.evaluate(p, m);
  ModelDerivatives d;
  model.derivatives(p, d);
  const StateModes sm = state_modes(m);
  const std::vector<StateSpace> dss = state_space_derivatives(m, d, count);

  LocalSensitivity out;
  for (const ParameterInfo& pi : info.parameters) out.parameters.push_back(pi.name);
  out.values = p;
  out.modes = oscillating_modes(model, p);
  std::vector<Eigen::Index> eig;
  for (const Eigen::Index e : sm.modes)
    if (sm.lambda[e].imag() > 0) eig.push_back(e);
  const Eigen::Index modes = static_cast<Eigen::Index>(eig.size());
  out.df_dp.resize(modes, count);
  out.dzeta_dp.resize(modes, count);
  out.f_normalized.resize(modes, count);
  out.zeta_normalized.resize(modes, count);
  for (Eigen::Index r = 0; r < modes; ++r) {
    const Eigen::Index e = eig[static_cast<std::size_t>(r)];
    const std::complex<double> lambda = sm.lambda[e];
    const double mag = std::abs(lambda), f = mag / kTwoPi, zeta = -lambda.real() / mag;
    for (int k = 0; k < count; ++k) {
      const std::complex<double> dlambda =
          (sm.left.row(e) * dss[static_cast<std::size_t>(k)].A.cast<std::complex<double>>() * sm.right.col(e))(0);
      const double dmag = (std::conj(lambda) * dlambda).real() / mag;
      const double df = dmag / kTwoPi;
      const double dzeta = -dlambda.real() / mag + lambda.real() * dmag / (mag * mag);
      out.df_dp(r, k) = df;
      out.dzeta_dp(r, k) = dzeta;
      out.f_normalized(r, k) = p[k] / f * df;
      out.zeta_normalized(r, k) = zeta != 0 ? p[k] / zeta * dzeta : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return out;
}

}  // namespace mbgen
