// Residues at given poles by least-squares frequency-domain fitting (LSFD), every channel at once: the basis
// depends on the poles and lines only, so one QR factorization serves all channels.
#include "lsfd_system.hpp"
#include "numerics/constants.hpp"

#include <cmath>

namespace mbgen {

namespace modal_detail {

using numerics::kTwoPi;

Eigen::MatrixXd stack_real(const Eigen::MatrixXcd& h) {
  Eigen::MatrixXd out(2 * h.rows(), h.cols());
  if (h.cols() == 0) return out;  // (a block below the top of an empty matrix would offset a null pointer)
  out.topRows(h.rows()) = h.real();
  out.bottomRows(h.rows()) = h.imag();
  return out;
}

LsfdSystem::LsfdSystem(const ModalData& data, const std::vector<std::complex<double>>& poles,
                       const LsfdOptions& options) {
  const Eigen::Index lines = data.f_hz.size();
  const Eigen::Index modes = static_cast<Eigen::Index>(poles.size());
  const int power = frf_quantity_power(data.quantity);
  const Eigen::Index lower = options.lower_residual ? 1 : 0, upper = options.upper_residual ? 1 : 0;
  basis_.resize(lines, 2 * modes + lower + upper);
  for (Eigen::Index k = 0; k < lines; ++k) {
    const std::complex<double> s(0, kTwoPi * data.f_hz[k]);
    const std::complex<double> sp = std::pow(s, power);
    for (Eigen::Index r = 0; r < modes; ++r) {
      const std::complex<double> phi = sp / (s - poles[static_cast<std::size_t>(r)]);
      const std::complex<double> phi_conj = sp / (s - std::conj(poles[static_cast<std::size_t>(r)]));
      basis_(k, 2 * r) = phi + phi_conj;
      basis_(k, 2 * r + 1) = std::complex<double>(0, 1) * (phi - phi_conj);
    }
    if (lower) basis_(k, 2 * modes) = sp / (s * s);
    if (upper) basis_(k, 2 * modes + lower) = sp;
  }
  Eigen::MatrixXd a = stack_real(basis_);
  scale_ = a.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < scale_.size(); ++j) scale_[j] = scale_[j] > 0 ? 1 / scale_[j] : 1;
  a *= scale_.asDiagonal();
  qr_.compute(a);
}

Eigen::MatrixXd LsfdSystem::solve(const Eigen::MatrixXcd& h) const {
  return scale_.asDiagonal() * qr_.solve(stack_real(h));
}

Eigen::MatrixXcd LsfdSystem::project_out(const Eigen::MatrixXcd& h) const {
  return h - basis_ * solve(h).cast<std::complex<double>>();
}

}  // namespace modal_detail

LsfdResult lsfd(const ModalData& data, const std::vector<std::complex<double>>& poles, const LsfdOptions& options) {
  const modal_detail::LsfdSystem system(data, poles, options);
  const Eigen::MatrixXd x = system.solve(data.H);
  const Eigen::Index modes = static_cast<Eigen::Index>(poles.size()), channels = data.H.cols();
  const int power = frf_quantity_power(data.quantity);
  const Eigen::Index lower = options.lower_residual ? 1 : 0;

  LsfdResult out;
  out.residues.resize(modes, channels);
  for (Eigen::Index r = 0; r < modes; ++r)
    for (Eigen::Index c = 0; c < channels; ++c)
      out.residues(r, c) =
          std::pow(poles[static_cast<std::size_t>(r)], power) * std::complex<double>(x(2 * r, c), x(2 * r + 1, c));
  out.lower = options.lower_residual ? Eigen::VectorXd(x.row(2 * modes).transpose()) : Eigen::VectorXd::Zero(channels);
  out.upper =
      options.upper_residual ? Eigen::VectorXd(x.row(2 * modes + lower).transpose()) : Eigen::VectorXd::Zero(channels);
  out.synthesized = system.basis() * x.cast<std::complex<double>>();
  out.channel_error.resize(channels);
  for (Eigen::Index c = 0; c < channels; ++c) {
    const double norm = data.H.col(c).norm();
    out.channel_error[c] = norm > 0 ? (data.H.col(c) - out.synthesized.col(c)).norm() / norm : 0.0;
  }
  return out;
}

}  // namespace mbgen
