#include "direct_solve.hpp"

#include <Eigen/SVD>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>

#include <cmath>
#include <complex>
#include <limits>

namespace mbgen::methods {

namespace {

using cd = std::complex<double>;

// The model's matrices and their derivatives with respect to the free parameters, on the coordinates used.
struct SetMatrices {
  Eigen::MatrixXd M, C, K, B;
  std::vector<Eigen::MatrixXd> dM, dC, dK, dB;  // per free parameter; zero when the data set sets it
  Eigen::VectorXd p;                            // the parameters for this set (reference plus `# set` values)
  std::vector<bool> known;                      // per free parameter: set by the data set
};

SetMatrices set_matrices(const Model& model, const DataSet& d, const std::vector<int>& coordinates,
                         const Eigen::VectorXd& reference, const std::vector<int>& free) {
  const ModelInfo& info = model.info();
  SetMatrices s;
  s.p = reference;
  std::vector<bool> overridden(info.parameters.size(), false);
  for (const auto& [name, value] : d.set()) {
    const int idx = info.parameter_index(name);
    if (idx < 0) throw FitError(d.file() + ": `# set " + name + "`: the model has no parameter " + name);
    s.p[idx] = value.value;
    overridden[static_cast<std::size_t>(idx)] = true;
  }
  ModelMatrices m;
  ModelDerivatives md;
  model.evaluate(s.p, m);
  model.derivatives(s.p, md);
  const auto nc = static_cast<Eigen::Index>(coordinates.size());
  std::vector<int> local(static_cast<std::size_t>(m.M.rows()), -1);
  for (Eigen::Index c = 0; c < nc; ++c) local[static_cast<std::size_t>(coordinates[static_cast<std::size_t>(c)])] = static_cast<int>(c);
  auto restrict = [&](const Eigen::MatrixXd& X, bool square) {
    Eigen::MatrixXd out(nc, square ? nc : X.cols());
    for (Eigen::Index r = 0; r < nc; ++r)
      for (Eigen::Index c = 0; c < out.cols(); ++c)
        out(r, c) = X(coordinates[static_cast<std::size_t>(r)], square ? coordinates[static_cast<std::size_t>(c)] : c);
    return out;
  };
  s.M = restrict(m.M, true);
  s.C = restrict(m.C, true);
  s.K = restrict(m.K, true);
  s.B = restrict(m.B, false);
  std::vector<int> column(info.parameters.size(), -1);
  for (std::size_t j = 0; j < free.size(); ++j) {
    s.known.push_back(overridden[static_cast<std::size_t>(free[j])]);
    if (!s.known.back()) column[static_cast<std::size_t>(free[j])] = static_cast<int>(j);
  }
  auto dense = [&](const std::vector<DerivativeEntry>& entries, Eigen::Index cols, bool square) {
    std::vector<Eigen::MatrixXd> out(free.size(), Eigen::MatrixXd::Zero(nc, cols));
    for (const auto& e : entries) {
      if (e.param < 0 || e.param >= static_cast<int>(column.size())) continue;
      const int j = column[static_cast<std::size_t>(e.param)];
      if (j < 0) continue;
      const int r = local[static_cast<std::size_t>(e.row)];
      const int c = square ? local[static_cast<std::size_t>(e.col)] : e.col;
      if (r < 0 || c < 0) continue;  // outside the coordinates used: no equation there
      out[static_cast<std::size_t>(j)](r, c) += e.value;
    }
    return out;
  };
  s.dM = dense(md.M, nc, true);
  s.dC = dense(md.C, nc, true);
  s.dK = dense(md.K, nc, true);
  s.dB = dense(md.B, m.B.cols(), false);
  return s;
}

Eigen::MatrixXd take(const Eigen::MatrixXd& X, const std::vector<int>& rows, const std::vector<int>& cols) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < cols.size(); ++c)
      out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = X(rows[r], cols[c]);
  return out;
}

Eigen::MatrixXd take_rows(const Eigen::MatrixXd& X, const std::vector<int>& rows) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), X.cols());
  for (std::size_t r = 0; r < rows.size(); ++r) out.row(static_cast<Eigen::Index>(r)) = X.row(rows[r]);
  return out;
}

}  // namespace

DirectSolution solve_direct(const Model& model, const std::vector<DataSet>& data, const DirectEquations& eq,
                            const Eigen::VectorXd& reference, const std::vector<int>& free,
                            const IdentifiabilityOptions& id_options, bool use_total) {
  const auto k = static_cast<Eigen::Index>(free.size());
  const auto nc = static_cast<Eigen::Index>(eq.coordinates.size());
  const Eigen::Index E = 2 * nc * eq.nuisance_groups;
  const Eigen::Index total = k + E + 1, cconst = k + E;

  std::vector<SetMatrices> sets;
  for (const DataSet& d : data) sets.push_back(set_matrices(model, d, eq.coordinates, reference, free));

  long complex_rows = 0;
  for (const EquationBlock& b : eq.blocks) complex_rows += static_cast<long>(b.rows.size());
  // The whitened equations, real parts over imaginary parts, kept as a tall matrix: a QR factorisation of it
  // (instead of the normal matrix) keeps the condition number from being squared, which a lightly damped
  // resonance (whitening weights 1/(2 zeta) times the others') makes large.
  Eigen::MatrixXd Aw(2 * complex_rows, total);
  Eigen::MatrixXd Sigma = Eigen::MatrixXd::Zero(k + 1, k + 1);  // free parameters, then the constant column
  std::vector<Eigen::MatrixXcd> raw;  // unwhitened columns per block, for the relative equation error
  std::vector<double> rhs_norm2;
  Eigen::Index row = 0;
  for (const EquationBlock& b : eq.blocks) {
    const SetMatrices& s = sets[static_cast<std::size_t>(b.set)];
    const auto n = static_cast<Eigen::Index>(b.rows.size());
    const cd iw(0, b.omega), pw = std::pow(iw, b.kind);
    auto Z = [&](const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K) {
      return Eigen::MatrixXcd(iw * iw * take(M, b.rows, b.rows).cast<cd>() + iw * take(C, b.rows, b.rows).cast<cd>() +
                              take(K, b.rows, b.rows).cast<cd>());
    };
    const Eigen::MatrixXcd Zref = Z(s.M, s.C, s.K);
    const Eigen::VectorXcd rhs = pw * (take_rows(s.B, b.rows).cast<cd>() * b.force);
    const Eigen::MatrixXcd whiten = Eigen::PartialPivLU<Eigen::MatrixXcd>(Zref * b.noise).inverse();
    Eigen::MatrixXcd A = Eigen::MatrixXcd::Zero(n, total);
    Eigen::MatrixXcd P(n * n, k + 1);  // noise of each whitened column: P_i xi, xi white
    Eigen::VectorXcd c0 = Zref * b.x - rhs;
    Eigen::MatrixXcd Z0 = Zref;
    for (Eigen::Index j = 0; j < k; ++j) {
      const auto js = static_cast<std::size_t>(j);
      const Eigen::MatrixXcd Zj = Z(s.dM[js], s.dC[js], s.dK[js]);
      const Eigen::VectorXcd cj = Zj * b.x - pw * (take_rows(s.dB[js], b.rows).cast<cd>() * b.force);
      const double pj = s.p[free[js]];
      c0 -= pj * cj;
      Z0 -= pj * Zj;
      A.col(j) = cj;
      const Eigen::MatrixXcd Pj = whiten * Zj * b.noise;
      P.col(j) = Eigen::Map<const Eigen::VectorXcd>(Pj.data(), n * n);
    }
    A.col(cconst) = c0;
    {
      const Eigen::MatrixXcd P0 = whiten * Z0 * b.noise;
      P.col(k) = Eigen::Map<const Eigen::VectorXcd>(P0.data(), n * n);
    }
    if (b.nuisance >= 0)
      for (Eigen::Index l = 0; l < n; ++l) {
        const Eigen::Index col = k + 2 * (b.nuisance * nc + b.rows[static_cast<std::size_t>(l)]);
        A(l, col) = iw;     // i w a_l
        A(l, col + 1) = 1;  // b_l
      }
    raw.push_back(A);
    rhs_norm2.push_back(rhs.squaredNorm());
    const Eigen::MatrixXcd W = whiten * A;
    Aw.middleRows(row, n) = W.real();
    Aw.middleRows(row + n, n) = W.imag();
    row += 2 * n;
    Sigma += (P.adjoint() * P).real();
  }

  // Columns scaled to unit norm; the end-term columns that occur first, so that the trailing block of R is the
  // parameters' and constant's part with the end terms eliminated (their Schur complement).
  Eigen::VectorXd D(total);
  for (Eigen::Index j = 0; j < total; ++j) {
    const double norm = Aw.col(j).norm();
    D[j] = norm > 0 ? 1 / norm : 1.0;
  }
  std::vector<int> order;  // columns of the factorised matrix
  Eigen::Index e_used = 0;
  for (Eigen::Index j = k; j < k + E; ++j)
    if (Aw.col(j).squaredNorm() > 0) {
      order.push_back(static_cast<int>(j));
      ++e_used;
    }
  for (Eigen::Index j = 0; j < k; ++j) order.push_back(static_cast<int>(j));
  order.push_back(static_cast<int>(cconst));
  const auto m_cols = static_cast<Eigen::Index>(order.size());
  Eigen::MatrixXd As(Aw.rows(), m_cols);
  for (Eigen::Index c = 0; c < m_cols; ++c) As.col(c) = Aw.col(order[static_cast<std::size_t>(c)]) * D[order[static_cast<std::size_t>(c)]];
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(As);
  const Eigen::MatrixXd Rfull = qr.matrixQR().topRows(std::min(m_cols, As.rows())).template triangularView<Eigen::Upper>();
  if (Rfull.rows() < m_cols) throw FitError("fit: --method direct: fewer equations than unknowns");
  const Eigen::MatrixXd R22 = Rfull.bottomRightCorner(k + 1, k + 1);  // theta_R's part, end terms eliminated
  Eigen::VectorXd DR(k + 1);
  for (Eigen::Index j = 0; j < k; ++j) DR[j] = D[j];
  DR[k] = D[cconst];
  const Eigen::MatrixXd Sr = DR.asDiagonal() * Sigma * DR.asDiagonal();

  DirectSolution out;
  out.equations = 2 * complex_rows;
  const Eigen::MatrixXd Rpp = R22.topLeftCorner(k, k);
  if (k > 0) {
    out.identifiability = analyse_identifiability(Rpp, id_options);
    const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(Rpp).singularValues();
    out.condition = sv[k - 1] > 0 ? sv[0] / sv[k - 1] : std::numeric_limits<double>::infinity();
  }
  // theta_R in scaled units, the constant's entry fixed so that its physical coefficient is 1.
  const double theta_c = 1 / DR[k];
  Eigen::VectorXd ls(k + 1);
  ls[k] = theta_c;
  if (k > 0)
    ls.head(k) = -Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(Rpp).solve(Eigen::VectorXd(R22.topRightCorner(k, 1))) * theta_c;
  Eigen::VectorXd theta = ls;
  // Total least squares: the largest eigenvalue mu of R^-T Sigma R^-1 (mu = 1 / lambda), when the equations do not
  // hold exactly (then R22 is regular; exact equations are solved exactly by LS).
  const double r_cc = std::abs(R22(k, k));
  if (use_total && k > 0 && Sr.norm() > 0 && r_cc > 1e-12 * R22.norm()) {
    const Eigen::MatrixXd Rinv = R22.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(k + 1, k + 1));
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Rinv.transpose() * Sr * Rinv);
    const double mu = es.eigenvalues()[k];
    const Eigen::VectorXd v = Rinv * es.eigenvectors().col(k);
    // A usable total solution needs the constant column in it (else the equations have no scale).
    if (mu > 0 && std::abs(v[k]) > 1e-12 * v.norm()) {
      theta = v * (theta_c / v[k]);
      out.total = true;
      out.noise_scale = 1 / mu;
    }
  }
  const double rss = (R22 * theta).squaredNorm();
  out.equation_rms = complex_rows > 0 ? std::sqrt(rss / double(complex_rows)) : 0;
  if (!out.total) {
    const double dof = double(out.equations) - double(k) - double(e_used);
    out.noise_scale = dof > 0 ? 2 * rss / dof : 0;  // the same lambda: complex variance
  }
  out.values = reference;
  out.ls_values = reference;
  for (Eigen::Index j = 0; j < k; ++j) {
    out.values[free[static_cast<std::size_t>(j)]] = DR[j] * theta[j];
    out.ls_values[free[static_cast<std::size_t>(j)]] = DR[j] * ls[j];
  }
  if (k > 0) {
    // First order: the whitened equation errors have variance lambda/2 per real part; the normal matrix of the
    // noise-free regressors is estimated by G - lambda Sigma (GTLS) or G (LS), G = Rpp^T Rpp.
    Eigen::MatrixXd info = Rpp.transpose() * Rpp;
    if (out.total) info -= out.noise_scale * Sr.topLeftCorner(k, k);
    const Eigen::MatrixXd cs = 0.5 * out.noise_scale * Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(info).pseudoInverse();
    const Eigen::VectorXd Dp = DR.head(k);
    out.covariance = Dp.asDiagonal() * cs * Dp.asDiagonal();
  }
  // End terms at their optimum for theta: R11 e + R12 theta = 0.
  Eigen::VectorXd full = Eigen::VectorXd::Zero(total);
  for (Eigen::Index j = 0; j < k; ++j) full[j] = theta[j];
  full[cconst] = theta[k];
  if (e_used > 0) {
    const Eigen::VectorXd e = -Rfull.topLeftCorner(e_used, e_used).triangularView<Eigen::Upper>().solve(
        Rfull.topRightCorner(e_used, k + 1) * theta);
    for (Eigen::Index j = 0; j < e_used; ++j) full[order[static_cast<std::size_t>(j)]] = e[j];
  }
  // Unweighted equation error at the solution.
  full = D.asDiagonal() * full;
  double e2 = 0, r2 = 0;
  for (std::size_t b = 0; b < raw.size(); ++b) {
    e2 += (raw[b] * full.cast<cd>()).squaredNorm();
    r2 += rhs_norm2[b];
  }
  out.relative_equation_error = r2 > 0 ? std::sqrt(e2 / r2) : 0;
  return out;
}

}  // namespace mbgen::methods
