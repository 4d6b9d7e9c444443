#include "mbgen_test/mdof2_data.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <complex>

namespace mbgen::test {

FrfData mdof2_frf_data(const Mdof2Values& v, const Eigen::VectorXd& f_hz, double relative_noise, std::mt19937& rng) {
  FrfData d;
  d.file = "mdof2-synthetic.csv";
  d.f_hz = f_hz;
  for (int c = 0; c < 2; ++c) {
    FrfChannel ch;
    ch.output = c == 0 ? "d1" : "d2";
    ch.input = "F1";
    ch.values.resize(f_hz.size());
    for (Eigen::Index k = 0; k < f_hz.size(); ++k) ch.values[k] = c == 0 ? mdof2_g11(v, f_hz[k]) : mdof2_g21(v, f_hz[k]);
    add_relative_noise(ch.values, relative_noise, rng);
    d.channels.push_back(ch);
  }
  return d;
}

void add_relative_noise(Eigen::VectorXcd& values, double relative_noise, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  const double level = std::sqrt(values.squaredNorm() / double(values.size()));
  for (Eigen::Index k = 0; k < values.size(); ++k)
    values[k] += level * relative_noise / std::sqrt(2.0) * std::complex<double>(normal(rng), normal(rng));
}

Eigen::MatrixXd zoh_modal_response(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K,
                                   const Eigen::MatrixXd& B, const Eigen::MatrixXd& Cd, const Eigen::MatrixXd& u,
                                   double h) {
  const Eigen::Index n = M.rows();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -M.inverse() * K;
  A.bottomRightCorner(n, n) = -M.inverse() * C;
  Eigen::MatrixXd Bs = Eigen::MatrixXd::Zero(2 * n, B.cols());
  Bs.bottomRows(n) = M.inverse() * B;
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  const Eigen::MatrixXcd V = es.eigenvectors();
  const Eigen::VectorXcd l = es.eigenvalues();
  const Eigen::MatrixXcd Vi = V.inverse();
  const Eigen::MatrixXcd Bm = Vi * Bs.cast<std::complex<double>>();
  const Eigen::MatrixXcd Cm = Cd.cast<std::complex<double>>() * V.topRows(n);
  Eigen::VectorXcd decay(2 * n), gain(2 * n);
  for (Eigen::Index i = 0; i < 2 * n; ++i) {
    decay[i] = std::exp(l[i] * h);
    gain[i] = (decay[i] - 1.0) / l[i];
  }
  Eigen::MatrixXd y(u.rows(), Cd.rows());
  Eigen::VectorXcd z = Eigen::VectorXcd::Zero(2 * n);
  for (Eigen::Index k = 0; k < u.rows(); ++k) {
    y.row(k) = (Cm * z).real().transpose();
    z = decay.cwiseProduct(z) + gain.cwiseProduct(Bm * u.row(k).transpose().cast<std::complex<double>>());
  }
  return y;
}

TimeRecord mdof2_time_record(const Mdof2Values& v, Eigen::Index samples, double h, double relative_noise,
                             std::mt19937& rng, double added_mass2) {
  ModelMatrices m = mdof2_matrices(v);
  m.M(1, 1) += added_mass2;
  std::normal_distribution<double> normal;
  Eigen::MatrixXd u(samples, 1);
  for (Eigen::Index k = 0; k < samples; ++k) u(k, 0) = 100 * normal(rng);
  const Eigen::MatrixXd y = zoh_modal_response(m.M, m.C, m.K, m.B, m.Cd, u, h);
  TimeRecord r;
  r.file = "mdof2-synthetic-time.csv";
  r.t = Eigen::VectorXd::LinSpaced(samples, 0, h * double(samples - 1));
  r.signals.push_back({"F1", u.col(0)});
  for (int o = 0; o < 2; ++o) {
    Eigen::VectorXd s = y.col(o);
    const double level = std::sqrt(s.squaredNorm() / double(samples));
    for (Eigen::Index k = 0; k < samples; ++k) s[k] += relative_noise * level * normal(rng);
    r.signals.push_back({o == 0 ? "d1" : "d2", s});
  }
  return r;
}

}  // namespace mbgen::test
