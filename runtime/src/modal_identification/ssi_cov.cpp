// Covariance-driven stochastic subspace identification (Peeters & De Roeck 1999): the responses' correlations
// factor as R_k = C A^(k-1) G, so their block Toeplitz matrix is the observability matrix times a controllability
// matrix; its SVD gives the observability matrix of each order, and A follows from its shift structure.
#include "mbgen/modal_identification/output_only_modal.hpp"
#include "numerics/constants.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mbgen {

namespace {

using numerics::kTwoPi;
constexpr int kDefaultMaxOrder = 48;  // 24 pole pairs: room for the modes and the noise's poles beside them
constexpr int kMinBlockRows = 32;

// T = [R_i R_(i-1) .. R_1; R_(i+1) .. R_2; ..; R_(2i-1) .. R_i]: block (a, b) is R_(i + a - b).
Eigen::MatrixXd block_toeplitz(const std::vector<Eigen::MatrixXd>& R, int i) {
  const Eigen::Index l = R.front().rows(), r = R.front().cols();
  Eigen::MatrixXd T(l * i, r * i);
  for (int a = 0; a < i; ++a)
    for (int b = 0; b < i; ++b) T.block(l * a, r * b, l, r) = R[static_cast<std::size_t>(i + a - b)];
  return T;
}

}  // namespace

SsiCovDiagram ssi_cov(const ResponseData& data, const SsiCovOptions& options) {
  const int l = static_cast<int>(data.channels.size());
  const int r = static_cast<int>(data.references.size());
  int max_order = options.max_order > 0 ? options.max_order : kDefaultMaxOrder;
  if (max_order % 2) ++max_order;  // poles come in conjugate pairs
  // A from the shift needs l (i - 1) >= n rows; the Toeplitz matrix's rank is at most r i.
  const int needed = std::max((max_order + l - 1) / l + 1, (max_order + r - 1) / r);
  const int i = options.block_rows > 0 ? options.block_rows : std::max(kMinBlockRows, needed);
  if (l * (i - 1) < max_order || r * i < max_order)
    throw std::invalid_argument("model order " + std::to_string(max_order) + " needs more block rows than " +
                                std::to_string(i) + " with " + std::to_string(l) + " channels and " +
                                std::to_string(r) + " references");

  SsiCovDiagram out;
  out.block_rows = i;
  const std::vector<Eigen::MatrixXd> R = output_correlations(data, 2 * i);
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(block_toeplitz(R, i), Eigen::ComputeThinU | Eigen::ComputeThinV);
  out.singular_values = svd.singularValues();
  StabilizationDiagram& d = out.diagram;
  d.references = r;
  d.dt = data.dt;
  d.lo_hz = 0;
  d.hi_hz = 0.5 / data.dt;
  const double nyquist = d.hi_hz;
  for (int n = 2; n <= max_order; n += 2) {
    d.orders.push_back(n);
    const Eigen::MatrixXd O =
        svd.matrixU().leftCols(n) * svd.singularValues().head(n).cwiseSqrt().asDiagonal();
    const Eigen::MatrixXd C = O.topRows(l);
    const Eigen::MatrixXd A = O.topRows(l * (i - 1)).colPivHouseholderQr().solve(O.bottomRows(l * (i - 1)));
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(A);
    // G = E[x_(t+1) y_ref,t^T] is the last block column of the controllability factor S^(1/2) V^T; the modal
    // factors of R_k = sum_m phi_m mu_m^(k-1) g_m^T are phi = C psi and g^T = psi^-1 G.
    const Eigen::MatrixXd G = svd.singularValues().head(n).cwiseSqrt().asDiagonal() *
                              svd.matrixV().leftCols(n).bottomRows(r).transpose();
    const Eigen::MatrixXcd g = eig.eigenvectors().fullPivLu().solve(G.cast<std::complex<double>>());
    std::vector<std::pair<DiagramPole, double>> poles;
    for (Eigen::Index k = 0; k < n; ++k) {
      const std::complex<double> mu = eig.eigenvalues()[k];
      if (mu.imag() <= 0 || std::abs(mu) <= 0) continue;  // one of each pair; real poles are no vibration
      DiagramPole p;
      p.order = n;
      p.lambda = std::log(mu) / data.dt;
      p.f_hz = std::abs(p.lambda) / kTwoPi;
      p.zeta = -p.lambda.real() / std::abs(p.lambda);
      if (!(p.f_hz > 0 && p.f_hz < nyquist)) continue;
      p.shape = C.cast<std::complex<double>>() * eig.eigenvectors().col(k);
      // The mode's resonance peak in the correlations' spectrum: |phi| |g| / |1 - |mu||.
      const double peak = p.shape.norm() * g.row(k).norm() / std::max(std::abs(1 - std::abs(mu)), 1e-300);
      poles.emplace_back(std::move(p), peak);
    }
    std::sort(poles.begin(), poles.end(), [](const auto& a, const auto& b) { return a.first.f_hz < b.first.f_hz; });
    double top = 0;
    for (const auto& p : poles) top = std::max(top, p.second);
    for (auto& p : poles) {
      d.poles.push_back(std::move(p.first));
      out.contribution.push_back(top > 0 ? p.second / top : 0.0);
    }
    if (options.progress) options.progress(n, max_order);
  }
  return out;
}

}  // namespace mbgen
