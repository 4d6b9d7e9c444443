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
    // Adjoint solve P^T Y^T = Cout^T; Yt = Y^T (n x outputs) is used directly: Y(o, r) = Yt(r, o).
    const Eigen::MatrixXcd Yt = lu.transpose().solve(Cout.transpose());
    result.lu_factorizations += 1;
    result.solved_columns += static_cast<std::size_t>(inputs + outputs);
    result.H.push_back(Cout * X);

    // Column p of J is vec(dH/dp_p); entry (o, i) lives in row o + i * outputs. Every derivative entry is a
    // rank-one (or row/column) update, written as plain loops: no temporaries.
    Eigen::MatrixXcd J = Eigen::MatrixXcd::Zero(outputs * inputs, parameter_count);
    // -Y dP X: each entry (r, c) of dP contributes -factor * Y(:, r) X(c, :).
    auto stiffness_term = [&](const std::vector<DerivativeEntry>& entries, cd factor) {
      for (const auto& e : entries) {
        const cd a = -factor * e.value;
        for (Eigen::Index i = 0; i < inputs; ++i) {
          const cd ax = a * X(e.col, i);
          for (Eigen::Index o = 0; o < outputs; ++o) J(o + i * outputs, e.param) += ax * Yt(e.row, o);
        }
      }
    };
    stiffness_term(d.K, 1.0);
    stiffness_term(d.C, s);
    stiffness_term(d.M, s2);
    // Y dB: entry (r, c) adds value * Y(:, r) to FRF column c.
    for (const auto& e : d.B)
      for (Eigen::Index o = 0; o < outputs; ++o) J(o + e.col * outputs, e.param) += e.value * Yt(e.row, o);
    // dCout X: entry (r, c) adds factor * value * X(c, :) to FRF row r.
    auto output_term = [&](const std::vector<DerivativeEntry>& entries, cd factor) {
      for (const auto& e : entries) {
        const cd a = factor * e.value;
        for (Eigen::Index i = 0; i < inputs; ++i) J(e.row + i * outputs, e.param) += a * X(e.col, i);
      }
    };
    output_term(d.Cd, 1.0);
    output_term(d.Cv, s);
    output_term(d.Ca, s2);
    result.dH.push_back(std::move(J));
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
