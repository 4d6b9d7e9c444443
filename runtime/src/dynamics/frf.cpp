#include "mbgen/frf.hpp"

#include "model_checks.hpp"
#include "mbgen/dynamics_error.hpp"

#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <sstream>

namespace mbgen {
namespace {

using cd = std::complex<double>;
constexpr double two_pi = 6.283185307179586476925286766559;

// P(jw) = K - w^2 M + jw C, factorised; throws if singular to working precision.
Eigen::PartialPivLU<Eigen::MatrixXcd> factor_dynamic_stiffness(const ModelMatrices& m, double f_hz,
                                                               const char* where) {
  const double w = two_pi * f_hz;
  Eigen::MatrixXcd P(m.M.rows(), m.M.cols());
  P.real() = m.K - (w * w) * m.M;
  P.imag() = w * m.C;
  Eigen::PartialPivLU<Eigen::MatrixXcd> lu(P);
  if (P.size() > 0) {
    const Eigen::VectorXd pivots = lu.matrixLU().diagonal().cwiseAbs();
    const double ratio = pivots.minCoeff() / pivots.maxCoeff();
    if (!(ratio > static_cast<double>(P.rows()) * std::numeric_limits<double>::epsilon())) {
      std::ostringstream msg;
      msg << where << ": dynamic stiffness K - w^2 M + jw C is singular at " << f_hz
          << " Hz (an undamped resonance, or a rigid-body mode at 0 Hz)";
      throw DynamicsError(msg.str());
    }
  }
  return lu;
}

Eigen::MatrixXcd output_matrix(const ModelMatrices& m, cd s) {
  return m.Cd.cast<cd>() + s * m.Cv.cast<cd>() + (s * s) * m.Ca.cast<cd>();
}

void check_frequencies(const std::vector<double>& freqs_hz, const char* where) {
  for (std::size_t k = 0; k < freqs_hz.size(); ++k)
    if (!std::isfinite(freqs_hz[k])) {
      std::ostringstream msg;
      msg << where << ": frequency " << k << " is not finite";
      throw DynamicsError(msg.str());
    }
}

}  // namespace

FrfResult frf(const ModelMatrices& m, const std::vector<double>& freqs_hz) {
  const char* where = "frf";
  detail::check_matrices(m, where);
  check_frequencies(freqs_hz, where);
  const Eigen::MatrixXcd B = m.B.cast<cd>();
  FrfResult result;
  result.freqs_hz = freqs_hz;
  result.H.reserve(freqs_hz.size());
  for (double f : freqs_hz) {
    const auto lu = factor_dynamic_stiffness(m, f, where);
    const cd s(0, two_pi * f);
    result.H.push_back(output_matrix(m, s) * lu.solve(B));
  }
  return result;
}

FrfJacobianResult frf_jacobian(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count,
                               const std::vector<double>& freqs_hz) {
  const char* where = "frf_jacobian";
  detail::check_matrices(m, where);
  detail::check_derivatives(m, d, parameter_count, where);
  check_frequencies(freqs_hz, where);
  const Eigen::Index outputs = m.Cd.rows(), inputs = m.B.cols();
  const Eigen::MatrixXcd B = m.B.cast<cd>();

  FrfJacobianResult result;
  result.freqs_hz = freqs_hz;
  result.H.reserve(freqs_hz.size());
  result.dH.reserve(freqs_hz.size());
  for (double f : freqs_hz) {
    const auto lu = factor_dynamic_stiffness(m, f, where);
    const cd s(0, two_pi * f), s2 = s * s;
    const Eigen::MatrixXcd Cout = output_matrix(m, s);
    const Eigen::MatrixXcd X = lu.solve(B);                                     // n x inputs
    const Eigen::MatrixXcd Yt = lu.transpose().solve(Cout.transpose());  // n x outputs: P^T Y^T = Cout^T
    const Eigen::MatrixXcd Y = Yt.transpose();                           // outputs x n
    result.lu_factorizations += 1;
    result.solved_columns += static_cast<std::size_t>(inputs + outputs);
    result.H.push_back(Cout * X);

    std::vector<Eigen::MatrixXcd> dH(static_cast<std::size_t>(parameter_count),
                                     Eigen::MatrixXcd::Zero(outputs, inputs));
    // -Y dP X: each entry (r, c) of dP contributes -factor * Y(:, r) X(c, :).
    auto stiffness_term = [&](const std::vector<DerivativeEntry>& entries, cd factor) {
      for (const auto& e : entries)
        dH[static_cast<std::size_t>(e.param)].noalias() -= (factor * e.value) * Y.col(e.row) * X.row(e.col);
    };
    stiffness_term(d.K, 1.0);
    stiffness_term(d.C, s);
    stiffness_term(d.M, s2);
    // Y dB: entry (r, c) adds Y(:, r) to column c.
    for (const auto& e : d.B) dH[static_cast<std::size_t>(e.param)].col(e.col) += e.value * Y.col(e.row);
    // dCout X: entry (r, c) adds X(c, :) to row r.
    auto output_term = [&](const std::vector<DerivativeEntry>& entries, cd factor) {
      for (const auto& e : entries)
        dH[static_cast<std::size_t>(e.param)].row(e.row) += (factor * e.value) * X.row(e.col);
    };
    output_term(d.Cd, 1.0);
    output_term(d.Cv, s);
    output_term(d.Ca, s2);
    result.dH.push_back(std::move(dH));
  }
  return result;
}

FrfResult frf(const Model& model, const Eigen::VectorXd& p, const std::vector<double>& freqs_hz) {
  detail::check_parameter_vector(model, p, "frf");
  ModelMatrices m;
  model.evaluate(p, m);
  return frf(m, freqs_hz);
}

FrfJacobianResult frf_jacobian(const Model& model, const Eigen::VectorXd& p, const std::vector<double>& freqs_hz) {
  detail::check_parameter_vector(model, p, "frf_jacobian");
  ModelMatrices m;
  ModelDerivatives d;
  model.evaluate(p, m);
  model.derivatives(p, d);
  return frf_jacobian(m, d, static_cast<int>(p.size()), freqs_hz);
}

}  // namespace mbgen
