#include "mbgen/state_modes.hpp"

#include "mbgen/dynamics_error.hpp"
#include "numerics/constants.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mbgen {

using numerics::kTwoPi;

double StateModes::f_hz(Eigen::Index e) const { return std::abs(lambda[e]) / kTwoPi; }

double StateModes::zeta(Eigen::Index e) const {
  const double mag = std::abs(lambda[e]);
  return mag > 0 ? -lambda[e].real() / mag : 0.0;
}

StateModes state_modes(const ModelMatrices& m) {
  StateModes out;
  out.ss = state_space(m);
  if (!out.ss.A.allFinite())  // 1e300 next to 1e-300: no double holds M^-1 K, and the iteration cannot converge
    throw DynamicsError("the model's state matrix (M^-1 K, M^-1 C) overflows a double at these parameter values "
                        "(masses and stiffnesses or dampings too far apart)");
  // x = [q; q'/s] with s the square root of the stiffness-to-mass scale: the two blocks of A become comparable
  // (the eigenvalues do not change; the eigenvectors are scaled back below).
  const Eigen::Index n = m.M.rows();
  const double s = std::sqrt(std::max(1.0, out.ss.A.bottomLeftCorner(n, n).cwiseAbs().maxCoeff()));
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(2 * n);
  scale.tail(n).setConstant(s);
  const Eigen::MatrixXd A = scale.cwiseInverse().asDiagonal() * out.ss.A * scale.asDiagonal();
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(A, /*computeEigenvectors=*/true);
  if (eig.info() != Eigen::Success) throw DynamicsError("the model's eigenvalue iteration did not converge");
  out.lambda = eig.eigenvalues();
  const Eigen::MatrixXcd V = eig.eigenvectors();
  out.right = scale.cast<std::complex<double>>().asDiagonal() * V;
  out.left = V.partialPivLu().inverse() * scale.cwiseInverse().cast<std::complex<double>>().asDiagonal();
  // Eigen's real Schur form gives real eigenvalues an imaginary part of exactly 0 and complex ones in pairs.
  for (Eigen::Index e = 0; e < out.lambda.size(); ++e)
    if (out.lambda[e].imag() >= 0) out.modes.push_back(e);
  std::stable_sort(out.modes.begin(), out.modes.end(), [&](Eigen::Index a, Eigen::Index b) {
    return out.f_hz(a) != out.f_hz(b) ? out.f_hz(a) < out.f_hz(b) : out.zeta(a) < out.zeta(b);
  });
  return out;
}

std::vector<ModeTerm> mode_terms(const StateModes& sm, const std::vector<Eigen::Index>& eigenvalues) {
  const Eigen::MatrixXcd CV = sm.ss.C.cast<std::complex<double>>() * sm.right;
  const Eigen::MatrixXcd WB = sm.left * sm.ss.B.cast<std::complex<double>>();
  const Eigen::Index outputs = sm.ss.C.rows(), inputs = sm.ss.B.cols(), states = sm.lambda.size();
  std::vector<ModeTerm> out;
  for (const Eigen::Index e : eigenvalues) {
    const std::complex<double> lambda = sm.lambda[e];
    const bool pair = lambda.imag() != 0;
    ModeTerm t;
    t.w = pair ? std::abs(lambda.imag()) : std::abs(lambda);
    const std::complex<double> s(0, t.w);
    t.term.resize(outputs, inputs);
    t.response.resize(outputs, inputs);
    for (Eigen::Index o = 0; o < outputs; ++o)
      for (Eigen::Index i = 0; i < inputs; ++i) {
        std::complex<double> h = sm.ss.D(o, i);
        for (Eigen::Index k = 0; k < states; ++k) h += CV(o, k) * WB(k, i) / (s - sm.lambda[k]);
        const std::complex<double> residue = CV(o, e) * WB(e, i);
        t.term(o, i) = std::abs(residue / (s - lambda) + (pair ? std::conj(residue) / (s - std::conj(lambda)) : 0.0));
        t.response(o, i) = std::abs(h);
      }
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace mbgen
