// Delta-method standard deviations of |H| and of the phase of a fitted model's FRF
// (mbgen/estimation/frf_confidence.hpp).
#include "mbgen/estimation/frf_confidence.hpp"

#include "mbgen/dynamics/frf.hpp"
#include "numerics/constants.hpp"

#include <algorithm>
#include <cmath>

namespace mbgen {

std::vector<FrfBand> frf_bands(const Model& model, const Eigen::VectorXd& values, const std::vector<int>& estimated,
                               const Eigen::MatrixXd& covariance, const std::vector<double>& f_hz,
                               const std::vector<std::pair<int, int>>& channels, const std::vector<int>& held) {
  const FrfJacobianResult J = frf_jacobian(model, values, f_hz);
  const auto lines = static_cast<Eigen::Index>(f_hz.size());
  const auto k = static_cast<Eigen::Index>(estimated.size());
  const double degrees = 180 / numerics::kPi;
  std::vector<FrfBand> bands;
  Eigen::VectorXd a(k), b(k);
  for (const auto& [output, input] : channels) {
    // Entry (output, input) of the FRF matrix in a column of dH (column-major, frf.hpp).
    const Eigen::Index entry = J.H.empty() ? 0 : output + input * J.H[0].rows();
    FrfBand& band = bands.emplace_back();
    band.H.resize(lines);
    band.magnitude_std.resize(lines);
    band.phase_std_deg.resize(lines);
    for (Eigen::Index f = 0; f < lines; ++f) {
      const auto line = static_cast<std::size_t>(f);
      const std::complex<double> h = J.H[line](output, input);
      const double magnitude = std::abs(h);
      for (Eigen::Index j = 0; j < k; ++j) {
        const int p = estimated[static_cast<std::size_t>(j)];
        const bool is_held = std::find(held.begin(), held.end(), p) != held.end();
        const std::complex<double> g = is_held ? std::complex<double>(0) : J.dH[line](entry, p);
        const std::complex<double> conj_h_g = std::conj(h) * g;
        a[j] = magnitude > 0 ? conj_h_g.real() / magnitude : std::abs(g);
        b[j] = magnitude > 0 ? conj_h_g.imag() / (magnitude * magnitude) : 0;
      }
      band.H[f] = h;
      band.magnitude_std[f] = std::sqrt(std::max(0.0, a.dot(covariance * a)));
      band.phase_std_deg[f] = degrees * std::sqrt(std::max(0.0, b.dot(covariance * b)));
    }
  }
  return bands;
}

FrfBand frf_band(const Model& model, const Eigen::VectorXd& values, const std::vector<int>& estimated,
                 const Eigen::MatrixXd& covariance, const std::vector<double>& f_hz, int output, int input,
                 const std::vector<int>& held) {
  return frf_bands(model, values, estimated, covariance, f_hz, {{output, input}}, held).front();
}

}  // namespace mbgen
