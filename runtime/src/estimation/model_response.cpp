#include "model_response.hpp"

#include "mbgen/fit.hpp"

#include <Eigen/LU>
#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>

namespace mbgen::estimation {

namespace {

void scatter(const std::vector<DerivativeEntry>& entries, const std::vector<int>& slot, Eigen::MatrixXd DenseDerivative::*member,
             std::vector<DenseDerivative>& out) {
  for (const auto& e : entries) {
    if (e.param < 0 || e.param >= static_cast<int>(slot.size())) continue;
    const int s = slot[static_cast<std::size_t>(e.param)];
    if (s < 0) continue;
    DenseDerivative& d = out[static_cast<std::size_t>(s)];
    Eigen::MatrixXd& X = d.*member;
    if (e.row < 0 || e.row >= X.rows() || e.col < 0 || e.col >= X.cols())
      throw FitError("model derivative entry out of range (parameter " + std::to_string(e.param) + ")");
    X(e.row, e.col) += e.value;
    if (e.value != 0) d.any = true;
  }
}

void check_entries(const std::vector<DerivativeEntry>& entries, const Eigen::MatrixXd& X, const char* matrix) {
  for (const auto& e : entries)
    if (e.row < 0 || e.row >= X.rows() || e.col < 0 || e.col >= X.cols())
      throw FitError(std::string("model derivative entry of ") + matrix + " out of range (parameter " +
                     std::to_string(e.param) + ", row " + std::to_string(e.row) + ", column " + std::to_string(e.col) + ")");
}

void check_derivative_entries(const ModelMatrices& m, const ModelDerivatives& d) {
  check_entries(d.M, m.M, "M");
  check_entries(d.C, m.C, "C");
  check_entries(d.K, m.K, "K");
  check_entries(d.B, m.B, "B");
  check_entries(d.Cd, m.Cd, "Cd");
  check_entries(d.Cv, m.Cv, "Cv");
  check_entries(d.Ca, m.Ca, "Ca");
}

}  // namespace

std::vector<DenseDerivative> dense_derivatives(const ModelMatrices& m, const ModelDerivatives& d,
                                               const std::vector<int>& params) {
  int count = 0;
  for (int p : params) count = std::max(count, p + 1);
  std::vector<int> slot(static_cast<std::size_t>(count), -1);
  for (std::size_t i = 0; i < params.size(); ++i) slot[static_cast<std::size_t>(params[i])] = static_cast<int>(i);
  std::vector<DenseDerivative> out(params.size());
  for (auto& x : out) {
    x.M = Eigen::MatrixXd::Zero(m.M.rows(), m.M.cols());
    x.C = Eigen::MatrixXd::Zero(m.C.rows(), m.C.cols());
    x.K = Eigen::MatrixXd::Zero(m.K.rows(), m.K.cols());
    x.B = Eigen::MatrixXd::Zero(m.B.rows(), m.B.cols());
    x.Cd = Eigen::MatrixXd::Zero(m.Cd.rows(), m.Cd.cols());
    x.Cv = Eigen::MatrixXd::Zero(m.Cv.rows(), m.Cv.cols());
    x.Ca = Eigen::MatrixXd::Zero(m.Ca.rows(), m.Ca.cols());
  }
  scatter(d.M, slot, &DenseDerivative::M, out);
  scatter(d.C, slot, &DenseDerivative::C, out);
  scatter(d.K, slot, &DenseDerivative::K, out);
  scatter(d.B, slot, &DenseDerivative::B, out);
  scatter(d.Cd, slot, &DenseDerivative::Cd, out);
  scatter(d.Cv, slot, &DenseDerivative::Cv, out);
  scatter(d.Ca, slot, &DenseDerivative::Ca, out);
  return out;
}

FrfResponse frf_response(const ModelMatrices& m, const ModelDerivatives* derivatives, const std::vector<int>& params,
                         const std::vector<int>& inactive, const Eigen::VectorXd& f_hz,
                         const std::vector<ChannelIndex>& channels) {
  using Complex = std::complex<double>;
  const Eigen::Index nf = f_hz.size();
  const Eigen::Index np = static_cast<Eigen::Index>(params.size());
  if (derivatives) check_derivative_entries(m, *derivatives);
  // Column of each model parameter in the Jacobian (-1: not wanted).
  std::vector<int> column;
  for (std::size_t j = 0; j < params.size(); ++j) {
    if (std::find(inactive.begin(), inactive.end(), params[j]) != inactive.end()) continue;
    if (params[j] >= static_cast<int>(column.size())) column.resize(static_cast<std::size_t>(params[j]) + 1, -1);
    column[static_cast<std::size_t>(params[j])] = static_cast<int>(j);
  }
  auto col_of = [&](int param) {
    return param >= 0 && param < static_cast<int>(column.size()) ? column[static_cast<std::size_t>(param)] : -1;
  };
  FrfResponse out;
  out.values.assign(channels.size(), Eigen::VectorXcd(nf));
  if (derivatives) out.jacobian.assign(channels.size(), Eigen::MatrixXcd::Zero(nf, np));
  const double two_pi = 2 * std::acos(-1.0);
  const Eigen::MatrixXcd Mc = m.M.cast<Complex>(), Cc = m.C.cast<Complex>(), Kc = m.K.cast<Complex>();
  const Eigen::MatrixXcd Bc = m.B.cast<Complex>();
  const Eigen::MatrixXcd Cdc = m.Cd.cast<Complex>(), Cvc = m.Cv.cast<Complex>(), Cac = m.Ca.cast<Complex>();
  Eigen::MatrixXcd P, c, X, Y;
  Eigen::PartialPivLU<Eigen::MatrixXcd> lu, lut;
  for (Eigen::Index k = 0; k < nf; ++k) {
    const double w = two_pi * f_hz[k];
    const Complex jw(0, w), s2(-w * w, 0);
    P = Kc + jw * Cc + s2 * Mc;
    lu.compute(P);
    X = lu.solve(Bc);
    c = Cdc + jw * Cvc + s2 * Cac;
    if (!X.allFinite()) throw FitError("singular dynamic stiffness at " + std::to_string(f_hz[k]) + " Hz");
    for (std::size_t ch = 0; ch < channels.size(); ++ch)
      out.values[ch][k] = (c.row(channels[ch].output) * X.col(channels[ch].input))(0, 0);
    if (!derivatives) continue;
    lut.compute(P.transpose());
    Y = lut.solve(c.transpose()).transpose();  // c P^-1
    // dH(o, i) = dc(o, :) X(:, i) + Y(o, :) (dB(:, i) - dP X(:, i)), entry by entry.
    for (std::size_t ch = 0; ch < channels.size(); ++ch) {
      const int o = channels[ch].output, i = channels[ch].input;
      auto& J = out.jacobian[ch];
      auto stiffness = [&](const std::vector<DerivativeEntry>& entries, Complex factor) {
        for (const auto& e : entries) {
          const int j = col_of(e.param);
          if (j >= 0) J(k, j) -= Y(o, e.row) * (factor * e.value) * X(e.col, i);
        }
      };
      stiffness(derivatives->K, Complex(1, 0));
      stiffness(derivatives->C, jw);
      stiffness(derivatives->M, s2);
      for (const auto& e : derivatives->B) {
        const int j = col_of(e.param);
        if (j >= 0 && e.col == i) J(k, j) += Y(o, e.row) * e.value;
      }
      auto output = [&](const std::vector<DerivativeEntry>& entries, Complex factor) {
        for (const auto& e : entries) {
          const int j = col_of(e.param);
          if (j >= 0 && e.row == o) J(k, j) += factor * e.value * X(e.col, i);
        }
      };
      output(derivatives->Cd, Complex(1, 0));
      output(derivatives->Cv, jw);
      output(derivatives->Ca, s2);
    }
  }
  return out;
}

namespace {

// State-space form: A, Bc, Cx, D from the second-order matrices.
struct StateSpace {
  Eigen::MatrixXd A, B, C, D;
};

StateSpace state_space(const Eigen::MatrixXd& M, const Eigen::MatrixXd& Cm, const Eigen::MatrixXd& K,
                       const Eigen::MatrixXd& Bm, const Eigen::MatrixXd& Cd, const Eigen::MatrixXd& Cv,
                       const Eigen::MatrixXd& Ca) {
  const Eigen::Index n = M.rows(), nu = Bm.cols(), ny = Cd.rows();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
  const Eigen::MatrixXd MiK = lu.solve(K), MiC = lu.solve(Cm), MiB = lu.solve(Bm);
  StateSpace s;
  s.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  s.A.topRightCorner(n, n).setIdentity();
  s.A.bottomLeftCorner(n, n) = -MiK;
  s.A.bottomRightCorner(n, n) = -MiC;
  s.B = Eigen::MatrixXd::Zero(2 * n, nu);
  s.B.bottomRows(n) = MiB;
  s.C.resize(ny, 2 * n);
  s.C.leftCols(n) = Cd - Ca * MiK;
  s.C.rightCols(n) = Cv - Ca * MiC;
  s.D = Ca * MiB;
  return s;
}

// Derivative of the state-space matrices: d(M^-1 X) = M^-1 (dX - dM M^-1 X).
StateSpace state_space_derivative(const ModelMatrices& m, const DenseDerivative& d) {
  const Eigen::Index n = m.M.rows(), nu = m.B.cols(), ny = m.Cd.rows();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(m.M);
  const Eigen::MatrixXd MiK = lu.solve(m.K), MiC = lu.solve(m.C), MiB = lu.solve(m.B);
  const Eigen::MatrixXd dMiK = lu.solve(d.K - d.M * MiK), dMiC = lu.solve(d.C - d.M * MiC),
                        dMiB = lu.solve(d.B - d.M * MiB);
  StateSpace s;
  s.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  s.A.bottomLeftCorner(n, n) = -dMiK;
  s.A.bottomRightCorner(n, n) = -dMiC;
  s.B = Eigen::MatrixXd::Zero(2 * n, nu);
  s.B.bottomRows(n) = dMiB;
  s.C.resize(ny, 2 * n);
  s.C.leftCols(n) = d.Cd - d.Ca * MiK - m.Ca * dMiK;
  s.C.rightCols(n) = d.Cv - d.Ca * MiC - m.Ca * dMiC;
  s.D = d.Ca * MiB + m.Ca * dMiB;
  return s;
}

// Exact discretisation of x' = A x + B u over dt: x+ = Phi x + G0 u_k + G1 (u_{k+1} - u_k), where G1 = 0 for a
// zero-order hold and the input ramps linearly between samples for a first-order hold. From the exponential
// of [[A dt, B dt, 0], [0, 0, I], [0, 0, 0]] (the (1,3) block is the integral of e^{A(dt - t)} B t/dt).
struct Discrete {
  Eigen::MatrixXd Phi, G0, G1;
};

Discrete discretise(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double dt, HoldMode hold) {
  const Eigen::Index n = A.rows(), nu = B.cols();
  const bool foh = hold == HoldMode::None;
  const Eigen::Index size = n + nu * (foh ? 2 : 1);
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(size, size);
  E.topLeftCorner(n, n) = A * dt;
  E.block(0, n, n, nu) = B * dt;
  if (foh) E.block(n, n + nu, nu, nu).setIdentity();
  const Eigen::MatrixXd F = E.exp();
  Discrete d;
  d.Phi = F.topLeftCorner(n, n);
  d.G0 = F.block(0, n, n, nu);
  d.G1 = foh ? Eigen::MatrixXd(F.block(0, n + nu, n, nu)) : Eigen::MatrixXd::Zero(n, nu);
  return d;
}

}  // namespace

TimeResponse time_response(const ModelMatrices& m, const std::vector<DenseDerivative>* derivatives,
                           const Eigen::MatrixXd& u, double dt, HoldMode hold, const std::vector<int>& outputs) {
  const StateSpace ss = state_space(m.M, m.C, m.K, m.B, m.Cd, m.Cv, m.Ca);
  const Eigen::Index ns = ss.A.rows(), nu = ss.B.cols(), N = u.rows();
  const std::size_t np = derivatives ? derivatives->size() : 0;
  const Discrete base = discretise(ss.A, ss.B, dt, hold);
  TimeResponse out;
  out.values.assign(outputs.size(), Eigen::VectorXd(N));
  // Input increments u_{k+1} - u_k (first-order hold; the last one is 0), one column per sample.
  Eigen::MatrixXd U = u.transpose(), dU = Eigen::MatrixXd::Zero(nu, N);
  if (N > 1) dU.leftCols(N - 1) = U.rightCols(N - 1) - U.leftCols(N - 1);
  // States x_k, one column per sample, starting at rest.
  Eigen::MatrixXd X(ns, N);
  {
    const Eigen::MatrixXd drive = base.G0 * U + base.G1 * dU;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(ns), next(ns);
    for (Eigen::Index k = 0; k < N; ++k) {
      X.col(k) = x;
      next.noalias() = base.Phi * x;
      x = next + drive.col(k);
    }
    if (!X.allFinite()) throw FitError("time simulation diverged (unstable model at these parameter values)");
  }
  const Eigen::MatrixXd Y = ss.C * X + ss.D * U;
  for (std::size_t o = 0; o < outputs.size(); ++o) out.values[o] = Y.row(outputs[o]).transpose();
  if (!derivatives) return out;
  out.sensitivity.assign(outputs.size(), Eigen::MatrixXd::Zero(N, static_cast<Eigen::Index>(np)));
  Eigen::MatrixXd S(ns, N);
  for (std::size_t j = 0; j < np; ++j) {
    const DenseDerivative& d = (*derivatives)[j];
    if (!d.any) continue;
    const StateSpace ds = state_space_derivative(m, d);
    // Augmented system z = [x; s]: z' = [[A, 0], [dA, A]] z + [[B], [dB]] u.
    Eigen::MatrixXd Aa = Eigen::MatrixXd::Zero(2 * ns, 2 * ns);
    Aa.topLeftCorner(ns, ns) = ss.A;
    Aa.bottomLeftCorner(ns, ns) = ds.A;
    Aa.bottomRightCorner(ns, ns) = ss.A;
    Eigen::MatrixXd Ba(2 * ns, nu);
    Ba.topRows(ns) = ss.B;
    Ba.bottomRows(ns) = ds.B;
    const Discrete aug = discretise(Aa, Ba, dt, hold);
    const Eigen::MatrixXd dPhi = aug.Phi.bottomLeftCorner(ns, ns);
    const Eigen::MatrixXd drive = dPhi * X + aug.G0.bottomRows(ns) * U + aug.G1.bottomRows(ns) * dU;
    Eigen::VectorXd s = Eigen::VectorXd::Zero(ns), next(ns);
    for (Eigen::Index k = 0; k < N; ++k) {
      S.col(k) = s;
      next.noalias() = base.Phi * s;
      s = next + drive.col(k);
    }
    const Eigen::MatrixXd dY = ds.C * X + ss.C * S + ds.D * U;
    for (std::size_t o = 0; o < outputs.size(); ++o)
      out.sensitivity[o].col(static_cast<Eigen::Index>(j)) = dY.row(outputs[o]).transpose();
  }
  return out;
}

}  // namespace mbgen::estimation
