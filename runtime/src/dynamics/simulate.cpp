#include "mbgen/dynamics/simulate.hpp"

#include "model_checks.hpp"
#include "mbgen/dynamics/dynamics_error.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <sstream>
#include <vector>

namespace mbgen {
namespace {

void check_inputs(const Eigen::MatrixXd& inputs, Eigen::Index expected, const char* where) {
  if (inputs.cols() != expected) {
    std::ostringstream msg;
    msg << where << ": the input record has " << inputs.cols() << " columns, the model has " << expected
        << " inputs";
    throw DynamicsError(msg.str());
  }
  if (!inputs.allFinite()) throw DynamicsError(std::string(where) + ": the input record has non-finite values");
}

// Phi = W B W^-1 with B block-diagonal: 1 x 1 blocks (real eigenvalues) and 2 x 2 blocks [[a, b], [-b, a]] (a pair
// a +- ib, W's columns the real and imaginary parts of the eigenvector of a + ib). In these coordinates a step of
// the recurrence costs O(n) per column instead of O(n^2).
struct RealModalForm {
  Eigen::MatrixXd W, W_inverse;
  std::vector<Eigen::Index> block_start;  // first row of each block
  std::vector<double> a, b;               // a block's [[a, b], [-b, a]]; b = 0 and one row for a real eigenvalue
  std::vector<bool> pair;
};

// False where Phi is defective or nearly so (W ill-conditioned: the sensitivities would lose digits), or its
// eigen-decomposition does not reproduce it; the caller then propagates in the original coordinates.
bool real_modal_form(const Eigen::MatrixXd& Phi, RealModalForm& out) {
  const Eigen::Index n = Phi.rows();
  if (n == 0) return false;
  Eigen::EigenSolver<Eigen::MatrixXd> es(Phi, true);
  if (es.info() != Eigen::Success) return false;
  const Eigen::VectorXcd lambda = es.eigenvalues();
  const Eigen::MatrixXcd V = es.eigenvectors();
  out.W.resize(n, n);
  out.block_start.clear();
  out.a.clear();
  out.b.clear();
  out.pair.clear();
  for (Eigen::Index i = 0; i < n;) {
    const double im = lambda[i].imag();
    out.block_start.push_back(i);
    out.a.push_back(lambda[i].real());
    if (im != 0.0) {
      // EigenSolver lists the two of a conjugate pair next to each other (the check below catches any other order).
      if (i + 1 >= n || lambda[i + 1] != std::conj(lambda[i])) return false;
      out.W.col(i) = V.col(i).real();
      out.W.col(i + 1) = V.col(i).imag();
      out.b.push_back(im);
      out.pair.push_back(true);
      i += 2;
    } else {
      out.W.col(i) = V.col(i).real();
      out.b.push_back(0.0);
      out.pair.push_back(false);
      i += 1;
    }
  }
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(out.W);
  out.W_inverse = lu.inverse();
  if (!out.W_inverse.allFinite()) return false;
  const double condition = out.W.lpNorm<Eigen::Infinity>() * out.W_inverse.lpNorm<Eigen::Infinity>();
  if (!(condition < 1e6)) return false;
  // Check the decomposition: W^-1 Phi W must be the block-diagonal B.
  Eigen::MatrixXd B = out.W_inverse * Phi * out.W;
  for (std::size_t k = 0; k < out.block_start.size(); ++k) {
    const Eigen::Index r = out.block_start[k];
    B(r, r) -= out.a[k];
    if (out.pair[k]) {
      B(r, r + 1) -= out.b[k];
      B(r + 1, r) += out.b[k];
      B(r + 1, r + 1) -= out.a[k];
    }
  }
  return B.lpNorm<Eigen::Infinity>() <= 1e-12 * std::max(1.0, Phi.lpNorm<Eigen::Infinity>());
}

// Z <- B Z, B the block-diagonal of `modal` (one step of the recurrence in modal coordinates).
void step_modal(const RealModalForm& modal, Eigen::MatrixXd& Z) {
  for (std::size_t m = 0; m < modal.block_start.size(); ++m) {
    const Eigen::Index r = modal.block_start[m];
    const double a = modal.a[m];
    if (modal.pair[m]) {
      const double c = modal.b[m];
      for (Eigen::Index col = 0; col < Z.cols(); ++col) {
        const double z0 = Z(r, col), z1 = Z(r + 1, col);
        Z(r, col) = a * z0 + c * z1;
        Z(r + 1, col) = -c * z0 + a * z1;
      }
    } else {
      Z.row(r) *= a;
    }
  }
}

}  // namespace

Eigen::MatrixXd simulate(const DiscreteStateSpace& system, const Eigen::MatrixXd& inputs) {
  check_inputs(inputs, system.Gamma0.cols(), "simulate");
  const Eigen::Index samples = inputs.rows();
  const Eigen::MatrixXd U = inputs.transpose();  // one column per sample: contiguous access in the loop
  Eigen::MatrixXd Y(system.C.rows(), samples);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(system.Phi.rows()), next(system.Phi.rows());
  const bool first_order = system.hold == InputHold::FirstOrder;
  for (Eigen::Index k = 0; k < samples; ++k) {
    Y.col(k).noalias() = system.C * x;
    Y.col(k).noalias() += system.D * U.col(k);
    if (k + 1 == samples) break;
    next.noalias() = system.Phi * x;
    next.noalias() += system.Gamma0 * U.col(k);
    if (first_order) next.noalias() += system.Gamma1 * U.col(k + 1);
    x.swap(next);
  }
  return Y.transpose();
}

Eigen::MatrixXd simulate(const ModelMatrices& m, const Eigen::MatrixXd& inputs, double dt, InputHold hold) {
  return simulate(discretize(state_space(m), dt, hold), inputs);
}

Eigen::MatrixXd simulate(const Model& model, const Eigen::VectorXd& p, const Eigen::MatrixXd& inputs, double dt,
                         InputHold hold) {
  detail::check_parameter_vector(model, p, "simulate");
  ModelMatrices m;
  model.evaluate(p, m);
  return simulate(m, inputs, dt, hold);
}

SimulationSensitivity simulate_with_sensitivity(const ModelMatrices& m, const ModelDerivatives& d,
                                                int parameter_count, const Eigen::MatrixXd& inputs, double dt,
                                                InputHold hold) {
  const StateSpace ss = state_space(m);
  const DiscreteStateSpace sys = discretize(ss, dt, hold);
  const std::vector<DiscreteStateSpace> dsys =
      discretize_derivatives(ss, state_space_derivatives(m, d, parameter_count), dt, hold);
  check_inputs(inputs, sys.Gamma0.cols(), "simulate_with_sensitivity");

  const Eigen::Index n = sys.Phi.rows(), ni = sys.Gamma0.cols(), no = sys.C.rows(), np = parameter_count;
  const Eigen::Index samples = inputs.rows();
  // Derivative matrices stacked vertically (block i belongs to p_i), so that one product gives the forcing of
  // all parameter sensitivities; its reshape to (rows x np) is a column-major Map.
  Eigen::MatrixXd dPhi(n * np, n), dGamma0(n * np, ni), dGamma1(n * np, ni), dC(no * np, n), dD(no * np, ni);
  for (Eigen::Index i = 0; i < np; ++i) {
    const DiscreteStateSpace& di = dsys[static_cast<std::size_t>(i)];
    dPhi.middleRows(i * n, n) = di.Phi;
    dGamma0.middleRows(i * n, n) = di.Gamma0;
    dGamma1.middleRows(i * n, n) = di.Gamma1;
    dC.middleRows(i * no, no) = di.C;
    dD.middleRows(i * no, no) = di.D;
  }

  const Eigen::MatrixXd U = inputs.transpose();
  const bool first_order = hold == InputHold::FirstOrder;

  // The states first: x_{k+1} = Phi x_k + Gamma0 u_k (+ Gamma1 u_{k+1}), from rest. The products with the small
  // system matrices are coefficient-wise (lazyProduct): Eigen's blocked kernels repack their operands on every
  // call, which costs more than the arithmetic at these sizes.
  Eigen::MatrixXd X(n, samples);
  if (samples > 0) X.col(0).setZero();
  for (Eigen::Index k = 0; k + 1 < samples; ++k) {
    X.col(k + 1).noalias() = sys.Phi.lazyProduct(X.col(k));
    X.col(k + 1).noalias() += sys.Gamma0.lazyProduct(U.col(k));
    if (first_order) X.col(k + 1).noalias() += sys.Gamma1.lazyProduct(U.col(k + 1));
  }
  // Outputs and the direct part of their sensitivities for all samples at once (large, efficient products):
  // y_k = C x_k + D u_k,  dy_k = C S_k + dC x_k + dD u_k.
  Eigen::MatrixXd Y(no, samples), dY(no * np, samples);
  Y.noalias() = sys.C * X;
  Y.noalias() += sys.D * U;
  dY.noalias() = dC * X;
  dY.noalias() += dD * U;

  // Sensitivities S_k = dx_k/dp (n x np): S_{k+1} = Phi S_k + dPhi x_k + dGamma0 u_k (+ dGamma1 u_{k+1}). The
  // forcing of a block of samples is one product with the stacked derivative matrices; its column j, reshaped
  // to (n x np), is the forcing of sample k0 + j.
  constexpr Eigen::Index block = 256;
  // In real modal coordinates (S = W Z, where Phi allows): Z_{k+1} = B Z_k + W^-1 F_k and C S_k = (C W) Z_k. The
  // forcing's transformation is folded into the stacked derivative matrices once; the recurrence below then steps
  // Z with B's small blocks instead of S with the dense Phi. Below, S holds Z in that case.
  RealModalForm modal;
  const bool in_modal_coordinates = samples > 1 && real_modal_form(sys.Phi, modal);
  Eigen::MatrixXd output_map = sys.C;
  if (in_modal_coordinates) {
    for (Eigen::Index i = 0; i < np; ++i) {
      dPhi.middleRows(i * n, n) = (modal.W_inverse * dPhi.middleRows(i * n, n)).eval();
      dGamma0.middleRows(i * n, n) = (modal.W_inverse * dGamma0.middleRows(i * n, n)).eval();
      if (first_order) dGamma1.middleRows(i * n, n) = (modal.W_inverse * dGamma1.middleRows(i * n, n)).eval();
    }
    output_map = sys.C * modal.W;
  }
  // Ss keeps the block's S_k side by side (column-major, so it is an n x (np b) matrix, as dY's block is an
  // no x (np b) one): the outputs' part of the whole block is then one large product.
  const Eigen::Index block_columns = std::min<Eigen::Index>(block, std::max<Eigen::Index>(samples - 1, 1));
  Eigen::MatrixXd F(n * np, block_columns), Ss(n * np, block_columns);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, np), next_S(n, np);
  for (Eigen::Index k0 = 0; k0 + 1 < samples; k0 += block) {
    const Eigen::Index b = std::min(block, samples - 1 - k0);
    F.leftCols(b).noalias() = dPhi * X.middleCols(k0, b);
    F.leftCols(b).noalias() += dGamma0 * U.middleCols(k0, b);
    if (first_order) F.leftCols(b).noalias() += dGamma1 * U.middleCols(k0 + 1, b);
    for (Eigen::Index j = 0; j < b; ++j) {
      Eigen::Map<Eigen::MatrixXd>(Ss.col(j).data(), n, np) = S;
      if (in_modal_coordinates) {
        step_modal(modal, S);
      } else {
        next_S.noalias() = sys.Phi.lazyProduct(S);
        S.swap(next_S);
      }
      S += Eigen::Map<const Eigen::MatrixXd>(F.col(j).data(), n, np);
    }
    Eigen::Map<Eigen::MatrixXd>(dY.col(k0).data(), no, np * b).noalias() +=
        output_map * Eigen::Map<const Eigen::MatrixXd>(Ss.data(), n, np * b);
  }
  if (samples > 0) Eigen::Map<Eigen::MatrixXd>(dY.col(samples - 1).data(), no, np).noalias() += output_map.lazyProduct(S);

  SimulationSensitivity result;
  result.outputs = Y.transpose();
  result.doutputs.reserve(static_cast<std::size_t>(np));
  for (Eigen::Index i = 0; i < np; ++i) result.doutputs.push_back(dY.middleRows(i * no, no).transpose());
  return result;
}

SimulationSensitivity simulate_with_sensitivity(const Model& model, const Eigen::VectorXd& p,
                                                const Eigen::MatrixXd& inputs, double dt, InputHold hold) {
  detail::check_parameter_vector(model, p, "simulate_with_sensitivity");
  ModelMatrices m;
  ModelDerivatives d;
  model.evaluate(p, m);
  model.derivatives(p, d);
  return simulate_with_sensitivity(m, d, static_cast<int>(p.size()), inputs, dt, hold);
}

}  // namespace mbgen
