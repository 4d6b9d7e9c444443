#include "mbgen/dynamics/state_space.hpp"

#include "dense_derivatives.hpp"
#include "matrix_checks.hpp"
#include "model_checks.hpp"

namespace mbgen {

StateSpace state_space(const ModelMatrices& m) {
  const char* where = "state_space";
  const auto lu = detail::factor_mass(m.M, where);
  detail::check_matrices(m, where);
  const Eigen::Index n = m.M.rows(), inputs = m.B.cols(), outputs = m.Cd.rows();
  const Eigen::MatrixXd MK = lu.solve(m.K), MC = lu.solve(m.C), MB = lu.solve(m.B);

  StateSpace ss;
  ss.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  ss.A.topRightCorner(n, n).setIdentity();
  ss.A.bottomLeftCorner(n, n) = -MK;
  ss.A.bottomRightCorner(n, n) = -MC;
  ss.B = Eigen::MatrixXd::Zero(2 * n, inputs);
  ss.B.bottomRows(n) = MB;
  ss.C.resize(outputs, 2 * n);
  ss.C.leftCols(n) = m.Cd - m.Ca * MK;
  ss.C.rightCols(n) = m.Cv - m.Ca * MC;
  ss.D = m.Ca * MB;
  return ss;
}

std::vector<StateSpace> state_space_derivatives(const ModelMatrices& m, const ModelDerivatives& d,
                                                int parameter_count) {
  const char* where = "state_space_derivatives";
  const auto lu = detail::factor_mass(m.M, where);
  detail::check_matrices(m, where);
  detail::check_derivatives(m, d, parameter_count, where);
  const Eigen::Index n = m.M.rows(), inputs = m.B.cols(), outputs = m.Cd.rows();
  const Eigen::MatrixXd MK = lu.solve(m.K), MC = lu.solve(m.C), MB = lu.solve(m.B);

  std::vector<StateSpace> result;
  result.reserve(static_cast<std::size_t>(parameter_count));
  for (const ModelMatrices& dm : detail::dense_derivatives(m, d, parameter_count)) {
    // d(M^-1 X) = M^-1 (dX - dM M^-1 X)
    const Eigen::MatrixXd dMK = lu.solve(dm.K - dm.M * MK);
    const Eigen::MatrixXd dMC = lu.solve(dm.C - dm.M * MC);
    const Eigen::MatrixXd dMB = lu.solve(dm.B - dm.M * MB);
    StateSpace ds;
    ds.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    ds.A.bottomLeftCorner(n, n) = -dMK;
    ds.A.bottomRightCorner(n, n) = -dMC;
    ds.B = Eigen::MatrixXd::Zero(2 * n, inputs);
    ds.B.bottomRows(n) = dMB;
    ds.C.resize(outputs, 2 * n);
    ds.C.leftCols(n) = dm.Cd - dm.Ca * MK - m.Ca * dMK;
    ds.C.rightCols(n) = dm.Cv - dm.Ca * MC - m.Ca * dMC;
    ds.D = dm.Ca * MB + m.Ca * dMB;
    result.push_back(std::move(ds));
  }
  return result;
}

}  // namespace mbgen
