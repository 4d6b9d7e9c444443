// Frequency response functions of M q'' + C q' + K q = B u, y = Cd q + Cv q' + Ca q'':
//
//   H(jw) = (Cd + jw Cv - w^2 Ca) P(jw)^-1 B,   P(jw) = -w^2 M + jw C + K,
//
// at a list of frequencies in Hz, for all outputs x inputs, and its exact derivatives with respect to every
// parameter. The derivative uses one LU factorisation of P per frequency and two block solves with it:
//
//   X = P^-1 B (direct),  Y = Cout P^-1 (adjoint, P^T Y^T = Cout^T),
//   dH/dp = dCout X - Y dP X + Y dB,
//
// where dP, dB, dCout come from the sparse DerivativeEntry lists, so each entry costs one rank-one update of
// an outputs x inputs block: the whole Jacobian costs about (inputs + outputs) triangular solves plus
// O(entries * outputs * inputs) per frequency, instead of one factorisation per parameter. The factorisation
// is a partial-pivoting LU written for the small dense P of lumped models, in buffers reused across frequencies.
#pragma once

#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <complex>
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

namespace mbgen {

struct FrfResult {
  std::vector<double> freqs_hz;
  std::vector<Eigen::MatrixXcd> H;  // H[k]: outputs x inputs at freqs_hz[k]
};

struct FrfJacobianResult {
  std::vector<double> freqs_hz;
  std::vector<Eigen::MatrixXcd> H;  // H[k]: outputs x inputs at freqs_hz[k]
  // dH[k]: (outputs * inputs) x parameters, the Jacobian block of frequency k: column p is vec(dH[k]/dp_p),
  // column-major like Eigen (entry (o, i) of the FRF matrix in row o + i * outputs). Use derivative() for one
  // parameter's outputs x inputs matrix.
  std::vector<Eigen::MatrixXcd> dH;
  // Work done, for benchmarks: LU factorisations of P and right-hand-side columns solved with them.
  std::size_t lu_factorizations = 0;
  std::size_t solved_columns = 0;

  Eigen::MatrixXcd derivative(std::size_t k, Eigen::Index p) const {
    return Eigen::Map<const Eigen::MatrixXcd>(dH[k].col(p).data(), H[k].rows(), H[k].cols());
  }
};

// Throws DynamicsError for inconsistent matrix sizes or a singular P at some frequency (an undamped resonance
// hit exactly, or f = 0 with a singular K).
FrfResult frf(const ModelMatrices& m, const std::vector<double>& freqs_hz);

// parameter_count: number of parameters p (every DerivativeEntry::param must lie in [0, parameter_count)).
FrfJacobianResult frf_jacobian(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count,
                               const std::vector<double>& freqs_hz);

// Streaming forms, for callers that consume one frequency at a time (the estimator's residuals): nothing is
// allocated per frequency. `sink` is called for k = 0, 1, ... in order with H (outputs x inputs) and, for the
// Jacobian, dH (layout of FrfJacobianResult::dH); both live in buffers that the next frequency overwrites.
// Same results and errors as the forms above.
using FrfSink = std::function<void(std::size_t k, const Eigen::MatrixXcd& H)>;
using FrfJacobianSink = std::function<void(std::size_t k, const Eigen::MatrixXcd& H, const Eigen::MatrixXcd& dH)>;
struct FrfWork {
  std::size_t lu_factorizations = 0;
  std::size_t solved_columns = 0;
};
FrfWork frf(const ModelMatrices& m, const std::vector<double>& freqs_hz, const FrfSink& sink);
FrfWork frf_jacobian(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count,
                     const std::vector<double>& freqs_hz, const FrfJacobianSink& sink);

// What an FRF evaluation leaves for a Jacobian evaluated next with the same matrices at the same frequencies (an
// estimator evaluates the residuals at a trial point and, once the step is accepted, their Jacobian there): P's
// factors and X = P^-1 B at every frequency. frf() given a cache fills it; frf_jacobian() given one takes the
// factors and X from it when the matrices and frequencies are exactly those it was filled with (they are compared),
// so it does only the adjoint solves, with bit-identical results; otherwise it works as without. Kept for dense
// factors of up to 2^18 entries over all lines (4 MiB: 1151 lines of a 15-coordinate P). One cache per thread.
class FrfFactorCache {
 public:
  FrfFactorCache();
  ~FrfFactorCache();
  FrfFactorCache(FrfFactorCache&&) noexcept;
  FrfFactorCache& operator=(FrfFactorCache&&) noexcept;

  struct Impl;  // frf.cpp
  Impl& impl() { return *impl_; }
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};
FrfWork frf(const ModelMatrices& m, const std::vector<double>& freqs_hz, const FrfSink& sink, FrfFactorCache* keep);
FrfWork frf_jacobian(const ModelMatrices& m, const ModelDerivatives& d, int parameter_count,
                     const std::vector<double>& freqs_hz, const FrfJacobianSink& sink, const FrfFactorCache* known);

// Conveniences: evaluate the model (and its derivatives) at parameters p first.
FrfResult frf(const Model& model, const Eigen::VectorXd& p, const std::vector<double>& freqs_hz);
FrfJacobianResult frf_jacobian(const Model& model, const Eigen::VectorXd& p, const std::vector<double>& freqs_hz);

}  // namespace mbgen
