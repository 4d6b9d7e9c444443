// Poles by the poly-reference least-squares complex-frequency method (PolyMAX; Peeters, Van der Auweraer,
// Guillaume, Leuridan 2004), order by order.
//
// Each row r of the fit (an output, or an input when the data have fewer outputs than inputs) is a row vector
// H_r(w) over the m references. The right matrix-fraction model is H_r = B_r A^-1 with
//   A(w) = sum_j Omega_j(w) alpha_j  (m x m),  B_r(w) = sum_j Omega_j(w) beta_rj  (1 x m),  j = 0..n,
// Omega_j(w) = exp(i w dt j), real coefficients. The linearized error w_r (B_r - H_r A) is linear in the
// coefficients; its real normal equations are
//   [R_r S_r; S_r^T T_r] per row, with beta_r eliminated: M = sum_r w_r^2 (T_r - S_r^T R_r^-1 S_r),
// and alpha_n = I fixes the scale: alpha_0..n-1 = -M11^-1 M12. Every block depends on j' - j only, so all of them
// come from sums over the lines at lags -n..n, computed once for the highest order: a lower order uses the
// leading blocks.
#include "mbgen/modal_identification/modal_identification.hpp"
#include "numerics/constants.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mbgen {

namespace {

using numerics::kTwoPi;

// rows[r][k]: the channel of row r at reference k.
struct Layout {
  int references = 1;
  bool transposed = false;
  std::vector<std::vector<int>> rows;
};

// A full outputs x inputs grid with more than one of each is fitted with the smaller side as references;
// anything else as common-denominator LSCF, one row per channel.
Layout fit_layout(const ModalData& data, bool poly_reference) {
  const std::size_t no = data.outputs.size(), ni = data.inputs.size();
  Layout layout;
  std::vector<int> grid(no * ni, -1);
  for (std::size_t c = 0; c < data.channels.size(); ++c)
    grid[static_cast<std::size_t>(data.channels[c].output) * ni + static_cast<std::size_t>(data.channels[c].input)] =
        static_cast<int>(c);
  const bool full = data.channels.size() == no * ni;
  if (poly_reference && full && no > 1 && ni > 1) {
    layout.transposed = ni > no;
    layout.references = static_cast<int>(std::min(no, ni));
    const std::size_t n_rows = std::max(no, ni);
    for (std::size_t r = 0; r < n_rows; ++r) {
      std::vector<int> row;
      for (std::size_t k = 0; k < static_cast<std::size_t>(layout.references); ++k)
        row.push_back(layout.transposed ? grid[k * ni + r] : grid[r * ni + k]);
      layout.rows.push_back(row);
    }
    return layout;
  }
  for (std::size_t c = 0; c < data.channels.size(); ++c) layout.rows.push_back({static_cast<int>(c)});
  return layout;
}

// Sums over the lines at lags -n..n of columns X: lag(d, c) = sum_f exp(i theta_f d) X(f, c).
class LagSums {
 public:
  LagSums(const Eigen::MatrixXcd& basis, const Eigen::MatrixXcd& x)
      : positive_(basis.transpose() * x), negative_(basis.adjoint() * x) {}
  std::complex<double> operator()(int d, Eigen::Index c) const { return d >= 0 ? positive_(d, c) : negative_(-d, c); }

 private:
  Eigen::MatrixXcd positive_, negative_;
};

}  // namespace

int lscf_default_max_order(const ModalData& data, int references) {
  const int by_modes = (64 + references - 1) / references;
  const int by_lines = static_cast<int>(data.f_hz.size()) / 4;
  return std::max(1, std::min(by_modes, by_lines));
}

StabilizationDiagram lscf(const ModalData& data, const LscfOptions& options) {
  const Layout layout = fit_layout(data, options.poly_reference);
  const int m = layout.references;
  const Eigen::Index lines = data.f_hz.size();
  const int n_max = options.max_order > 0 ? options.max_order : lscf_default_max_order(data, m);
  const Eigen::Index lines_needed = 2 * static_cast<Eigen::Index>(n_max);  // in an int, 2 * n_max may overflow
  if (lines_needed > lines)
    throw std::invalid_argument("the highest order " + std::to_string(n_max) + " needs at least " +
                                std::to_string(lines_needed) + " lines in the band; it holds " + std::to_string(lines));

  StabilizationDiagram diagram;
  diagram.references = m;
  diagram.transposed = layout.transposed;
  diagram.lo_hz = data.f_hz[0];
  diagram.hi_hz = data.f_hz[lines - 1];
  diagram.dt = 1.0 / (2.0 * diagram.hi_hz);

  // The basis at non-negative lags: basis(f, d) = exp(i w_f dt d).
  Eigen::MatrixXcd basis(lines, n_max + 1);
  for (Eigen::Index f = 0; f < lines; ++f) {
    const double theta = kTwoPi * data.f_hz[f] * diagram.dt;
    for (int d = 0; d <= n_max; ++d) basis(f, d) = std::polar(1.0, theta * d);
  }
  const std::size_t n_rows = layout.rows.size();
  // Columns: every channel (for S), then per row the products conj(H_k) H_k' (for T).
  const Eigen::Index products = static_cast<Eigen::Index>(m) * m;
  Eigen::MatrixXcd x(lines,
                     static_cast<Eigen::Index>(data.channels.size() + n_rows * static_cast<std::size_t>(products)));
  x.leftCols(data.H.cols()) = data.H;
  std::vector<double> weight2(n_rows);
  for (std::size_t r = 0; r < n_rows; ++r) {
    double power = 0;
    for (int k = 0; k < m; ++k) power += data.H.col(layout.rows[r][static_cast<std::size_t>(k)]).squaredNorm();
    // Every row counts alike, whatever its units or level.
    weight2[r] = power > 0 ? static_cast<double>(lines * m) / power : 0.0;
    for (int k = 0; k < m; ++k)
      for (int k2 = 0; k2 < m; ++k2)
        x.col(data.H.cols() + static_cast<Eigen::Index>(r) * products + k * m + k2) =
            data.H.col(layout.rows[r][static_cast<std::size_t>(k)])
                .conjugate()
                .cwiseProduct(data.H.col(layout.rows[r][static_cast<std::size_t>(k2)]));
  }
  const LagSums lag(basis, x);
  const Eigen::VectorXd r_lag = basis.transpose().rowwise().sum().real();  // sum_f cos(theta_f d), d >= 0

  for (int n = 1; n <= n_max; ++n) {
    const Eigen::Index nb = n + 1, na = static_cast<Eigen::Index>(m) * (n + 1);
    Eigen::MatrixXd R(nb, nb);
    for (Eigen::Index j = 0; j < nb; ++j)
      for (Eigen::Index j2 = 0; j2 < nb; ++j2) R(j, j2) = r_lag[std::abs(j2 - j)];
    const Eigen::LDLT<Eigen::MatrixXd> R_ldlt(R);
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(na, na);
    std::vector<Eigen::MatrixXd> S(n_rows);
    for (std::size_t r = 0; r < n_rows; ++r) {
      S[r].resize(nb, na);
      Eigen::MatrixXd T(na, na);
      for (Eigen::Index j = 0; j < nb; ++j)
        for (Eigen::Index j2 = 0; j2 < nb; ++j2) {
          const int d = static_cast<int>(j2 - j);
          for (int k = 0; k < m; ++k) {
            S[r](j, j2 * m + k) = -lag(d, layout.rows[r][static_cast<std::size_t>(k)]).real();
            for (int k2 = 0; k2 < m; ++k2)
              T(j * m + k, j2 * m + k2) =
                  lag(d, data.H.cols() + static_cast<Eigen::Index>(r) * products + k * m + k2).real();
          }
        }
      M.noalias() += weight2[r] * (T - S[r].transpose() * R_ldlt.solve(S[r]));
    }
    // alpha_n = I: the first m n unknowns from the reduced equations.
    const Eigen::Index nl = static_cast<Eigen::Index>(m) * n;
    Eigen::MatrixXd alpha(na, m);
    alpha.topRows(nl) = -M.topLeftCorner(nl, nl).ldlt().solve(M.topRightCorner(nl, m));
    alpha.bottomRows(m).setIdentity();

    // Companion matrix of A(z) = sum_j z^j alpha_j: eigenvector [v; z v; ...; z^(n-1) v] with A(z) v = 0.
    Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(nl, nl);
    if (n > 1) companion.topRightCorner(nl - m, nl - m).setIdentity();
    for (int j = 0; j < n; ++j)
      companion.block(nl - m, static_cast<Eigen::Index>(j) * m, m, m) = -alpha.block(j * m, 0, m, m);
    // With one reference the null vector v is the scalar 1: no eigenvectors needed (they cost most of the solve).
    Eigen::EigenSolver<Eigen::MatrixXd> eig(companion, /*computeEigenvectors=*/m > 1);
    if (eig.info() != Eigen::Success) continue;  // no poles at this order
    std::vector<Eigen::MatrixXd> beta(n_rows);
    for (std::size_t r = 0; r < n_rows; ++r) beta[r] = -R_ldlt.solve(S[r] * alpha);  // (n+1) x m

    std::vector<DiagramPole> poles;
    for (Eigen::Index e = 0; e < nl; ++e) {
      const std::complex<double> z = eig.eigenvalues()[e];
      if (!(z.imag() > 0)) continue;  // one member of each conjugate pair; real poles are not modes
      DiagramPole p;
      p.order = n;
      p.lambda = std::log(z) / diagram.dt;
      p.f_hz = std::abs(p.lambda) / kTwoPi;
      if (p.f_hz < diagram.lo_hz || p.f_hz > diagram.hi_hz) continue;
      p.zeta = -p.lambda.real() / std::abs(p.lambda);
      const Eigen::VectorXcd v =
          m > 1 ? Eigen::VectorXcd(eig.eigenvectors().col(e).head(m)) : Eigen::VectorXcd::Ones(1);
      p.shape.resize(static_cast<Eigen::Index>(n_rows));
      for (std::size_t r = 0; r < n_rows; ++r) {
        std::complex<double> zj = 1, value = 0;
        for (Eigen::Index j = 0; j < nb; ++j, zj *= z)
          value += zj * (beta[r].row(j).cast<std::complex<double>>() * v)(0);
        p.shape[static_cast<Eigen::Index>(r)] = value;
      }
      poles.push_back(std::move(p));
    }
    std::stable_sort(poles.begin(), poles.end(),
                     [](const DiagramPole& a, const DiagramPole& b) { return a.f_hz < b.f_hz; });
    diagram.orders.push_back(n);
    for (DiagramPole& p : poles) diagram.poles.push_back(std::move(p));
    if (options.progress) options.progress(n, n_max);
  }
  return diagram;
}

}  // namespace mbgen
