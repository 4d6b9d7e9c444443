// The linear least-squares problem of LSFD at given poles (lsfd.cpp), shared with the pole refinement
// (refine.cpp), which needs its basis, its factorization and its projection.
#pragma once

#include "mbgen/modal_identification/modal_identification.hpp"

#include <Eigen/QR>

#include <complex>
#include <vector>

namespace mbgen::modal_detail {

// Complex basis columns, a real coefficient each: per mode r, for the receptance residue R = a + i b,
//   a (phi + conj-phi) + b i (phi - conj-phi),  phi = s^p / (s - lambda), conj-phi = s^p / (s - conj(lambda)),
// then s^(p-2) (lower residual) and s^p (upper residual); s = i w, p the quantity's power.
class LsfdSystem {
 public:
  LsfdSystem(const ModalData& data, const std::vector<std::complex<double>>& poles, const LsfdOptions& options);

  Eigen::Index unknowns() const { return basis_.cols(); }
  const Eigen::MatrixXcd& basis() const { return basis_; }  // lines x unknowns
  // The real coefficients of every channel (unknowns x channels), least squares on the stacked real and
  // imaginary parts.
  Eigen::MatrixXd solve(const Eigen::MatrixXcd& h) const;
  // The part of h (lines x k) that the basis cannot represent: h minus its least-squares projection.
  Eigen::MatrixXcd project_out(const Eigen::MatrixXcd& h) const;

 private:
  Eigen::MatrixXcd basis_;
  Eigen::VectorXd scale_;  // column scaling of the real system, for its conditioning
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_;
};

Eigen::MatrixXd stack_real(const Eigen::MatrixXcd& h);

}  // namespace mbgen::modal_detail
