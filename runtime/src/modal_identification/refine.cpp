// Pole refinement by variable projection: the residues and residual terms are linear in the data given the
// poles (LSFD), so the misfit is a function of the poles alone, r(theta) = P_perp(theta) H (Golub & Pereyra 1973).
// Its Jacobian is taken in Kaufman's form, dr/dtheta ~ -P_perp (dPhi/dtheta) x, which drops a term that vanishes
// with the residual; Levenberg-Marquardt with Marquardt's diagonal scaling minimizes ||r||^2.
#include "lsfd_system.hpp"

#include <Eigen/Cholesky>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace mbgen {

namespace {

using modal_detail::LsfdSystem;
using modal_detail::stack_real;

constexpr double kTwoPi = 6.283185307179586476925286766559;

// theta = (sigma_0, omega_0, sigma_1, ...), lambda = -sigma + i omega.
std::vector<std::complex<double>> poles_of(const Eigen::VectorXd& theta) {
  std::vector<std::complex<double>> poles;
  for (Eigen::Index r = 0; 2 * r < theta.size(); ++r) poles.emplace_back(-theta[2 * r], theta[2 * r + 1]);
  return poles;
}

struct Evaluation {
  double cost = 0;
  Eigen::VectorXd residual;  // stacked real and imaginary parts, channel after channel
  Eigen::MatrixXd jacobian;
};

Evaluation evaluate(const ModalData& data, const Eigen::MatrixXcd& hw, const Eigen::VectorXd& theta,
                    const LsfdOptions& lsfd_options, bool with_jacobian) {
  const std::vector<std::complex<double>> poles = poles_of(theta);
  const LsfdSystem system(data, poles, lsfd_options);
  const Eigen::MatrixXd x = system.solve(hw);
  const Eigen::MatrixXcd r = hw - system.basis() * x.cast<std::complex<double>>();
  Evaluation e;
  const Eigen::MatrixXd rs = stack_real(r);
  e.residual = Eigen::Map<const Eigen::VectorXd>(rs.data(), rs.size());
  e.cost = e.residual.squaredNorm();
  if (!with_jacobian) return e;

  const Eigen::Index lines = data.f_hz.size(), channels = hw.cols(), modes = static_cast<Eigen::Index>(poles.size());
  const int power = frf_quantity_power(data.quantity);
  // dModel/dtheta for every parameter and channel, side by side: column (2 r + {0 sigma, 1 omega}) * channels + c.
  Eigen::MatrixXcd d(lines, 2 * modes * channels);
  for (Eigen::Index k = 0; k < lines; ++k) {
    const std::complex<double> s(0, kTwoPi * data.f_hz[k]);
    const std::complex<double> sp = std::pow(s, power);
    for (Eigen::Index m = 0; m < modes; ++m) {
      const std::complex<double> lambda = poles[static_cast<std::size_t>(m)];
      const std::complex<double> dphi = sp / ((s - lambda) * (s - lambda));
      const std::complex<double> dphi_conj = sp / ((s - std::conj(lambda)) * (s - std::conj(lambda)));
      for (Eigen::Index c = 0; c < channels; ++c) {
        const std::complex<double> residue(x(2 * m, c), x(2 * m + 1, c));
        // model = R phi + conj(R) conj-phi; d lambda / d sigma = -1, d lambda / d omega = i.
        d(k, (2 * m) * channels + c) = -(residue * dphi + std::conj(residue) * dphi_conj);
        d(k, (2 * m + 1) * channels + c) = std::complex<double>(0, 1) * (residue * dphi - std::conj(residue) * dphi_conj);
      }
    }
  }
  const Eigen::MatrixXd projected = stack_real(system.project_out(d));
  e.jacobian.resize(e.residual.size(), 2 * modes);
  for (Eigen::Index p = 0; p < 2 * modes; ++p)
    for (Eigen::Index c = 0; c < channels; ++c)
      e.jacobian.block(c * 2 * lines, p, 2 * lines, 1) = -projected.col(p * channels + c);
  return e;
}

std::string percent(double x) {
  std::ostringstream s;
  s << std::setprecision(3) << 100 * x << " %";
  return s.str();
}

}  // namespace

RefinedPoles refine_poles(const ModalData& data, const std::vector<std::complex<double>>& poles,
                          const LsfdOptions& lsfd_options, const RefineOptions& options) {
  RefinedPoles out;
  out.poles = poles;
  const std::size_t n = poles.size();
  out.f_std_hz.assign(n, std::numeric_limits<double>::quiet_NaN());
  out.zeta_std.assign(n, std::numeric_limits<double>::quiet_NaN());
  if (n == 0) return out;

  // Each channel weighted by 1 / its RMS.
  Eigen::MatrixXcd hw = data.H;
  for (Eigen::Index c = 0; c < hw.cols(); ++c) {
    const double norm = hw.col(c).norm();
    if (norm > 0) hw.col(c) *= std::sqrt(static_cast<double>(hw.rows())) / norm;
  }
  Eigen::VectorXd theta(2 * static_cast<Eigen::Index>(n));
  for (std::size_t r = 0; r < n; ++r) {
    theta[2 * static_cast<Eigen::Index>(r)] = -poles[r].real();
    theta[2 * static_cast<Eigen::Index>(r) + 1] = poles[r].imag();
  }
  const Eigen::VectorXd start = theta;
  Evaluation e = evaluate(data, hw, theta, lsfd_options, true);
  out.initial_cost = e.cost;
  double mu = -1;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::MatrixXd jtj = e.jacobian.transpose() * e.jacobian;
    const Eigen::VectorXd g = e.jacobian.transpose() * e.residual;
    const Eigen::VectorXd diag = jtj.diagonal().cwiseMax(1e-300);
    if (mu < 0) mu = 1e-3;
    bool accepted = false;
    for (int tries = 0; tries < 30 && !accepted; ++tries) {
      Eigen::MatrixXd a = jtj;
      a.diagonal() += mu * diag;
      const Eigen::VectorXd step = -a.ldlt().solve(g);
      const Eigen::VectorXd trial = theta + step;
      bool valid = trial.allFinite();
      for (Eigen::Index r = 0; valid && 2 * r < trial.size(); ++r) valid = trial[2 * r] > 0 && trial[2 * r + 1] > 0;
      const double trial_cost = valid ? evaluate(data, hw, trial, lsfd_options, false).cost : 0;
      if (valid && trial_cost < e.cost) {
        const double decrease = (e.cost - trial_cost) / e.cost;
        theta = trial;
        e = evaluate(data, hw, theta, lsfd_options, true);
        mu = std::max(mu / 3, 1e-12);
        accepted = true;
        out.iterations = it + 1;
        if (decrease < 1e-12 || step.norm() < 1e-12 * theta.norm()) it = options.max_iterations;
      } else {
        mu *= 4;
      }
    }
    if (!accepted) break;
  }
  out.cost = e.cost;

  // Keep the refined poles only when each stays near where LSCF put it and physical.
  std::vector<std::complex<double>> refined = poles_of(theta);
  out.refined = true;
  for (std::size_t r = 0; r < n && out.refined; ++r) {
    const double f0 = std::abs(poles[r]), f1 = std::abs(refined[r]);
    const double zeta = -refined[r].real() / f1;
    std::ostringstream why;
    if (std::abs(f1 - f0) > options.max_shift * f0)
      why << "the pole near " << std::setprecision(6) << f0 / kTwoPi << " Hz would move by " << percent(std::abs(f1 - f0) / f0);
    else if (!(zeta > 0 && zeta <= options.max_zeta))
      why << "the pole near " << std::setprecision(6) << f0 / kTwoPi << " Hz would get zeta " << zeta;
    if (!why.str().empty()) {
      out.refined = false;
      out.note = why.str();
    }
  }
  if (!out.refined) {
    theta = start;
    e = evaluate(data, hw, theta, lsfd_options, true);
    out.cost = e.cost;
  } else {
    out.poles = refined;
  }

  // Covariance of theta: s^2 (J^T J)^-1 with s^2 the misfit per degree of freedom (the linear unknowns of every
  // channel and the poles count against the data).
  const double dof = static_cast<double>(e.residual.size()) - static_cast<double>(theta.size()) -
                     static_cast<double>(hw.cols()) * static_cast<double>(LsfdSystem(data, out.poles, lsfd_options).unknowns());
  if (dof > 0) {
    const Eigen::MatrixXd cov = (e.cost / dof) * (e.jacobian.transpose() * e.jacobian).ldlt().solve(
                                                     Eigen::MatrixXd::Identity(theta.size(), theta.size()));
    for (std::size_t r = 0; r < n; ++r) {
      const Eigen::Index i = 2 * static_cast<Eigen::Index>(r);
      const double sigma = theta[i], omega = theta[i + 1], mag = std::hypot(sigma, omega);
      const Eigen::Vector2d df(sigma / mag / kTwoPi, omega / mag / kTwoPi);
      const Eigen::Vector2d dz(omega * omega / (mag * mag * mag), -sigma * omega / (mag * mag * mag));
      const Eigen::Matrix2d c = cov.block<2, 2>(i, i);
      out.f_std_hz[r] = std::sqrt(std::max(0.0, df.dot(c * df)));
      out.zeta_std[r] = std::sqrt(std::max(0.0, dz.dot(c * dz)));
    }
  }
  return out;
}

}  // namespace mbgen
