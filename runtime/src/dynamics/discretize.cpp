#include "mbgen/dynamics/state_space.hpp"

#include "numerics/balance.hpp"
#include "matrix_checks.hpp"
#include "mbgen/dynamics/dynamics_error.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>
#include <sstream>

namespace mbgen {
namespace {

void check_state_space(const StateSpace& ss, const char* where) {
  const Eigen::Index n = ss.A.rows();
  detail::require_square(ss.A, n, "A", where);
  detail::require_shape(ss.B, n, ss.B.cols(), "B", where);
  detail::require_shape(ss.C, ss.C.rows(), n, "C", where);
  detail::require_shape(ss.D, ss.C.rows(), ss.B.cols(), "D", where);
}

void check_dt(double dt, const char* where) {
  if (std::isfinite(dt) && dt > 0) return;
  std::ostringstream msg;
  msg << where << ": sampling interval dt = " << dt << " must be positive and finite";
  throw DynamicsError(msg.str());
}

// The augmented matrix whose exponential holds Phi and the input integrals, in balanced coordinates
// (A_s = S^-1 A S, B_s = S^-1 B with S = diag(scale)).
//   ZOH: [[A_s T, B_s T], [0, 0]]              -> exp: [[Phi_s, G0_s], [0, I]]
//   FOH: [[A_s T, B_s T, 0], [0, 0, I], [0, 0, 0]] -> exp: [[Phi_s, Ga_s, Gb_s], ...]
// with Ga = int_0^T e^{As} ds B and Gb = (1/T) int_0^T e^{As} (T - s) ds B.
Eigen::MatrixXd augmented(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::VectorXd& scale,
                          double dt, InputHold hold, bool with_identity) {
  const Eigen::Index n = A.rows(), m = B.cols();
  const Eigen::Index size = n + (hold == InputHold::FirstOrder ? 2 * m : m);
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(size, size);
  F.topLeftCorner(n, n) = scale.cwiseInverse().asDiagonal() * A * scale.asDiagonal() * dt;
  F.block(0, n, n, m) = scale.cwiseInverse().asDiagonal() * B * dt;
  if (hold == InputHold::FirstOrder && with_identity) F.block(n, n + m, m, m).setIdentity();
  return F;
}

// Unpacks the top block row of an exponential (or its derivative) into Phi, Gamma0, Gamma1, undoing the scaling.
void unpack(const Eigen::MatrixXd& E, Eigen::Index n, Eigen::Index m, const Eigen::VectorXd& scale, InputHold hold,
            DiscreteStateSpace& out) {
  out.Phi = scale.asDiagonal() * E.topLeftCorner(n, n) * scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd Ga = scale.asDiagonal() * E.block(0, n, n, m);
  if (hold == InputHold::ZeroOrder) {
    out.Gamma0 = Ga;
    out.Gamma1 = Eigen::MatrixXd::Zero(n, m);
  } else {
    // x(T) = Phi x(0) + Ga u0 + Gb (u1 - u0).
    const Eigen::MatrixXd Gb = scale.asDiagonal() * E.block(0, n + m, n, m);
    out.Gamma0 = Ga - Gb;
    out.Gamma1 = Gb;
  }
}

}  // namespace

DiscreteStateSpace discretize(const StateSpace& ss, double dt, InputHold hold) {
  const char* where = "discretize";
  check_state_space(ss, where);
  check_dt(dt, where);
  if (!ss.A.allFinite() || !ss.B.allFinite()) throw DynamicsError("discretize: A or B has non-finite entries");
  const Eigen::Index n = ss.A.rows(), m = ss.B.cols();
  const Eigen::VectorXd scale = numerics::balancing_scale(ss.A);
  const Eigen::MatrixXd E = augmented(ss.A, ss.B, scale, dt, hold, true).exp();
  DiscreteStateSpace out;
  unpack(E, n, m, scale, hold, out);
  out.C = ss.C;
  out.D = ss.D;
  out.dt = dt;
  out.hold = hold;
  return out;
}

std::vector<DiscreteStateSpace> discretize_derivatives(const StateSpace& ss, const std::vector<StateSpace>& ds,
                                                       double dt, InputHold hold) {
  const char* where = "discretize_derivatives";
  check_state_space(ss, where);
  check_dt(dt, where);
  const Eigen::Index n = ss.A.rows(), m = ss.B.cols();
  const Eigen::VectorXd scale = numerics::balancing_scale(ss.A);
  const Eigen::MatrixXd F = augmented(ss.A, ss.B, scale, dt, hold, true);
  const Eigen::Index size = F.rows();

  std::vector<DiscreteStateSpace> result;
  result.reserve(ds.size());
  Eigen::MatrixXd V = Eigen::MatrixXd::Zero(2 * size, 2 * size);
  V.topLeftCorner(size, size) = F;
  V.bottomRightCorner(size, size) = F;
  for (std::size_t i = 0; i < ds.size(); ++i) {
    const StateSpace& d = ds[i];
    try {
      check_state_space(d, where);
      detail::require_shape(d.A, n, n, "dA", where);
      detail::require_shape(d.B, n, m, "dB", where);
      detail::require_shape(d.C, ss.C.rows(), n, "dC", where);
    } catch (const DynamicsError& e) {
      throw DynamicsError(std::string(e.what()) + " (derivative " + std::to_string(i) + ")");
    }
    // Van Loan: the top-right block of exp([[F, dF], [0, F]]) is the derivative of exp(F) along dF. That
    // derivative is linear in dF, so dF is scaled to the norm of F first: a huge or tiny dF (a derivative
    // with respect to a small mass, a damping) would otherwise distort the scaling-and-squaring of the
    // exponential.
    const Eigen::MatrixXd dF = augmented(d.A, d.B, scale, dt, hold, false);
    const double dF_norm = dF.cwiseAbs().colwise().sum().maxCoeff();
    DiscreteStateSpace out;
    if (dF_norm == 0) {
      unpack(Eigen::MatrixXd::Zero(size, size), n, m, scale, hold, out);
    } else {
      const double F_norm = F.cwiseAbs().colwise().sum().maxCoeff();
      const double alpha = F_norm > 0 ? F_norm / dF_norm : 1.0;
      V.topRightCorner(size, size) = alpha * dF;
      const Eigen::MatrixXd E = V.exp();
      unpack(E.topRightCorner(size, size) / alpha, n, m, scale, hold, out);
    }
    out.C = d.C;
    out.D = d.D;
    out.dt = dt;
    out.hold = hold;
    result.push_back(std::move(out));
  }
  return result;
}

}  // namespace mbgen
