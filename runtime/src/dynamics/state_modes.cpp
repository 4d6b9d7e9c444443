#include "mbgen/dynamics/state_modes.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"
#include "numerics/constants.hpp"
#include "numerics/state_eigen.hpp"

#include <cmath>
#include <stdexcept>

namespace mbgen {

double StateModes::f_hz(Eigen::Index e) const { return numerics::pole_frequency_hz(lambda[e]); }

double StateModes::zeta(Eigen::Index e) const { return numerics::pole_damping_ratio(lambda[e]); }

StateModes state_modes(const ModelMatrices& m) {
  StateModes out;
  out.ss = state_space(m);
  if (!out.ss.A.allFinite())  // 1e300 next to 1e-300: no double holds M^-1 K, and the iteration cannot converge
    throw DynamicsError("the model's state matrix (M^-1 K, M^-1 C) overflows a double at these parameter values "
                        "(masses and stiffnesses or dampings too far apart)");
  auto eig = numerics::state_eigen(out.ss.A, numerics::EigenVectors::right_and_left,
                                  numerics::Scaling::velocity_block);
  if (!eig) throw DynamicsError("the model's eigenvalue iteration did not converge");
  out.lambda = std::move(eig->lambda);
  out.right = std::move(eig->right);
  out.left = std::move(eig->left);
  out.modes = numerics::listed_modes(out.lambda);
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
    t.share.resize(outputs, inputs);
    for (Eigen::Index o = 0; o < outputs; ++o)
      for (Eigen::Index i = 0; i < inputs; ++i) {
        std::complex<double> h = sm.ss.D(o, i);
        for (Eigen::Index k = 0; k < states; ++k) h += CV(o, k) * WB(k, i) / (s - sm.lambda[k]);
        const std::complex<double> residue = CV(o, e) * WB(e, i);
        t.term(o, i) = std::abs(residue / (s - lambda) + (pair ? std::conj(residue) / (s - std::conj(lambda)) : 0.0));
        t.response(o, i) = std::abs(h);
        t.share(o, i) = t.response(o, i) > 0 ? t.term(o, i) / t.response(o, i) : 0.0;
      }
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace mbgen
