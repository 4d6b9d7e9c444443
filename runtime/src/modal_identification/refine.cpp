// Pole refinement by variable projection: the residues and residual terms are linear in the data given the
// poles (LSFD), so the misfit is a function of the poles alone, r(theta) = P_perp(theta) H (Golub & Pereyra 1973).
// Its Jacobian is taken in Kaufman's form, dr/dtheta ~ -P_perp (dPhi/dtheta) x, which drops a term that vanishes
// with the residual; Levenberg-Marquardt with Marquardt's diagonal scaling minimizes ||r||^2.
#include "lsfd_system.hpp"
#include "numerics/constants.hpp"

#include <Eigen/Cholesky>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace mbgen {

namespace {

using modal_detail::LsfdSystem;
using modal_detail::stack_real;

using numerics::kTwoPi;

// The poles being refined, as theta = (sigma, omega) of each active pole (lambda = -sigma + i omega), beside the
// poles held fixed.
struct PoleSet {
  std::vector<std::complex<double>> poles;
  std::vector<std::size_t> active;

  Eigen::VectorXd theta() const {
    Eigen::VectorXd t(2 * static_cast<Eigen::Index>(active.size()));
    for (std::size_t a = 0; a < active.size(); ++a) {
      t[2 * static_cast<Eigen::Index>(a)] = -poles[active[a]].real();
      t[2 * static_cast<Eigen::Index>(a) + 1] = poles[active[a]].imag();
    }
    return t;
  }
  std::vector<std::complex<double>> with(const Eigen::VectorXd& theta) const {
    std::vector<std::complex<double>> out = poles;
    for (std::size_t a = 0; a < active.size(); ++a)
      out[active[a]] = {-theta[2 * static_cast<Eigen::Index>(a)], theta[2 * static_cast<Eigen::Index>(a) + 1]};
    return out;
  }
};

struct Evaluation {
  double cost = 0;
  Eigen::VectorXd residual;  // stacked real and imaginary parts, channel after channel
  Eigen::MatrixXd jacobian;  // with respect to the active poles' theta
};

Evaluation evaluate(const ModalData& data, const Eigen::MatrixXcd& hw, const PoleSet& set, const Eigen::VectorXd& theta,
                    const LsfdOptions& lsfd_options, bool with_jacobian) {
  const std::vector<std::complex<double>> poles = set.with(theta);
  const LsfdSystem system(data, poles, lsfd_options);
  const Eigen::MatrixXd x = system.solve(hw);
  const Eigen::MatrixXcd r = hw - system.basis() * x.cast<std::complex<double>>();
  Evaluation e;
  const Eigen::MatrixXd rs = stack_real(r);
  e.residual = Eigen::Map<const Eigen::VectorXd>(rs.data(), rs.size());
  e.cost = e.residual.squaredNorm();
  if (!with_jacobian || set.active.empty()) return e;

  const Eigen::Index lines = data.f_hz.size(), channels = hw.cols();
  const Eigen::Index active = static_cast<Eigen::Index>(set.active.size());
  const int power = frf_quantity_power(data.quantity);
  // dModel/dtheta of channel c for mode m, with the receptance residue R = a + i b:
  //   d/dsigma = -(R g1 + conj(R) g2),  d/domega = i R g1 - i conj(R) g2,  g1 = s^p / (s - lambda)^2,
  //   g2 = s^p / (s - conj(lambda))^2.
  // Stacked real, a complex multiple (u + i v) g is u stack(g) + v stack(i g): every channel's column combines
  // the same four real vectors per mode, so only those are projected (not one column per channel and parameter).
  Eigen::MatrixXcd g(lines, 4 * active);  // per mode: g1, i g1, g2, i g2
  for (Eigen::Index k = 0; k < lines; ++k) {
    const std::complex<double> s(0, kTwoPi * data.f_hz[k]);
    const std::complex<double> sp = std::pow(s, power);
    for (Eigen::Index a = 0; a < active; ++a) {
      const std::complex<double> lambda = poles[set.active[static_cast<std::size_t>(a)]];
      const std::complex<double> g1 = sp / ((s - lambda) * (s - lambda));
      const std::complex<double> g2 = sp / ((s - std::conj(lambda)) * (s - std::conj(lambda)));
      g(k, 4 * a) = g1;
      g(k, 4 * a + 1) = std::complex<double>(0, 1) * g1;
      g(k, 4 * a + 2) = g2;
      g(k, 4 * a + 3) = std::complex<double>(0, 1) * g2;
    }
  }
  const Eigen::MatrixXd pg = stack_real(system.project_out(g));  // P_perp of each, 2 lines x 4 active
  e.jacobian.resize(e.residual.size(), 2 * active);
  for (Eigen::Index a = 0; a < active; ++a) {
    const Eigen::Index m = static_cast<Eigen::Index>(set.active[static_cast<std::size_t>(a)]);
    for (Eigen::Index c = 0; c < channels; ++c) {
      const double re = x(2 * m, c), im = x(2 * m + 1, c);
      // J = -P_perp dModel/dtheta.
      e.jacobian.block(c * 2 * lines, 2 * a, 2 * lines, 1) =
          re * pg.col(4 * a) + im * pg.col(4 * a + 1) + re * pg.col(4 * a + 2) - im * pg.col(4 * a + 3);
      e.jacobian.block(c * 2 * lines, 2 * a + 1, 2 * lines, 1) =
          im * pg.col(4 * a) - re * pg.col(4 * a + 1) + im * pg.col(4 * a + 2) + re * pg.col(4 * a + 3);
    }
  }
  return e;
}

// Levenberg-Marquardt with Marquardt's diagonal scaling from theta; returns the last accepted theta.
Eigen::VectorXd minimize(const ModalData& data, const Eigen::MatrixXcd& hw, const PoleSet& set, Eigen::VectorXd theta,
                         const LsfdOptions& lsfd_options, int max_iterations, int& iterations) {
  iterations = 0;
  if (theta.size() == 0) return theta;  // every pole held: nothing to move
  Evaluation e = evaluate(data, hw, set, theta, lsfd_options, true);
  double mu = 1e-3;
  for (int it = 0; it < max_iterations; ++it) {
    const Eigen::MatrixXd jtj = e.jacobian.transpose() * e.jacobian;
    const Eigen::VectorXd g = e.jacobian.transpose() * e.residual;
    const Eigen::VectorXd diag = jtj.diagonal().cwiseMax(1e-300);
    bool accepted = false, converged = false;
    for (int tries = 0; tries < 30 && !accepted; ++tries) {
      Eigen::MatrixXd a = jtj;
      a.diagonal() += mu * diag;
      const Eigen::VectorXd step = -a.ldlt().solve(g);
      const Eigen::VectorXd trial = theta + step;
      bool valid = trial.allFinite();
      for (Eigen::Index r = 0; valid && 2 * r < trial.size(); ++r) valid = trial[2 * r] > 0 && trial[2 * r + 1] > 0;
      const double trial_cost = valid ? evaluate(data, hw, set, trial, lsfd_options, false).cost : 0;
      if (valid && trial_cost < e.cost) {
        converged = (e.cost - trial_cost) / e.cost < 1e-12 || step.norm() < 1e-12 * theta.norm();
        theta = trial;
        e = evaluate(data, hw, set, theta, lsfd_options, true);
        mu = std::max(mu / 3, 1e-12);
        accepted = true;
        iterations = it + 1;
      } else {
        mu *= 4;
      }
    }
    if (!accepted || converged) break;
  }
  return theta;
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
  out.refined.assign(n, false);
  out.notes.assign(n, "");
  out.f_std_hz.assign(n, std::numeric_limits<double>::quiet_NaN());
  out.zeta_std.assign(n, std::numeric_limits<double>::quiet_NaN());
  if (n == 0) return out;

  // Each channel weighted by 1 / its RMS.
  Eigen::MatrixXcd hw = data.H;
  for (Eigen::Index c = 0; c < hw.cols(); ++c) {
    const double norm = hw.col(c).norm();
    if (norm > 0) hw.col(c) *= std::sqrt(static_cast<double>(hw.rows())) / norm;
  }
  PoleSet set{poles, {}};
  for (std::size_t r = 0; r < n; ++r) set.active.push_back(r);
  out.initial_cost = evaluate(data, hw, set, set.theta(), lsfd_options, false).cost;

  // A pole that would wander off (more than max_shift in frequency, or out of 0 < zeta <= max_zeta) is not a
  // mode the data determine: it is held at its LSCF value and the others are refined again from the start.
  Eigen::VectorXd theta;
  for (;;) {
    theta = minimize(data, hw, set, set.theta(), lsfd_options, options.max_iterations, out.iterations);
    const std::vector<std::complex<double>> refined = set.with(theta);
    std::vector<std::size_t> keep;
    for (const std::size_t r : set.active) {
      const double w0 = std::abs(poles[r]), w1 = std::abs(refined[r]);
      const double zeta = -refined[r].real() / w1;
      std::ostringstream why;
      if (std::abs(w1 - w0) > options.max_shift * w0)
        why << "the pole near " << std::setprecision(6) << w0 / kTwoPi << " Hz would move by "
            << percent(std::abs(w1 - w0) / w0);
      else if (!(zeta > 0 && zeta <= options.max_zeta))
        why << "the pole near " << std::setprecision(6) << w0 / kTwoPi << " Hz would get zeta " << zeta;
      if (why.str().empty())
        keep.push_back(r);
      else
        out.notes[r] = why.str();
    }
    if (keep.size() == set.active.size()) break;
    set.active = keep;
  }
  out.poles = set.with(theta);
  for (const std::size_t r : set.active) out.refined[r] = true;
  const Evaluation e = evaluate(data, hw, set, theta, lsfd_options, true);
  out.cost = e.cost;

  // Covariance of the refined poles' theta: s^2 (J^T J)^-1 with s^2 the misfit per degree of freedom (the linear
  // unknowns of every channel and the refined poles count against the data).
  const double dof =
      static_cast<double>(e.residual.size()) - static_cast<double>(theta.size()) -
      static_cast<double>(hw.cols()) * static_cast<double>(LsfdSystem(data, out.poles, lsfd_options).unknowns());
  if (dof > 0 && theta.size() > 0) {
    const Eigen::MatrixXd cov =
        (e.cost / dof) *
        (e.jacobian.transpose() * e.jacobian).ldlt().solve(Eigen::MatrixXd::Identity(theta.size(), theta.size()));
    for (std::size_t a = 0; a < set.active.size(); ++a) {
      const Eigen::Index i = 2 * static_cast<Eigen::Index>(a);
      const double sigma = theta[i], omega = theta[i + 1], mag = std::hypot(sigma, omega);
      const Eigen::Vector2d df(sigma / mag / kTwoPi, omega / mag / kTwoPi);
      const Eigen::Vector2d dz(omega * omega / (mag * mag * mag), -sigma * omega / (mag * mag * mag));
      const Eigen::Matrix2d c = cov.block<2, 2>(i, i);
      out.f_std_hz[set.active[a]] = std::sqrt(std::max(0.0, df.dot(c * df)));
      out.zeta_std[set.active[a]] = std::sqrt(std::max(0.0, dz.dot(c * dz)));
    }
  }
  return out;
}

}  // namespace mbgen
