#include "direct_solve.hpp"

#include <Eigen/SVD>
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
                            const IdentifiabilityOptions& id_options, bool instrumental) {
  const auto k = static_cast<Eigen::Index>(free.size());
  const auto nc = static_cast<Eigen::Index>(eq.coordinates.size());
  const Eigen::Index E = 2 * nc * eq.nuisance_groups;
  const Eigen::Index total = k + E + 1, cconst = k + E;

  std::vector<SetMatrices> sets;
  for (const DataSet& d : data) sets.push_back(set_matrices(model, d, eq.coordinates, reference, free));

  long complex_rows = 0;
  for (const EquationBlock& b : eq.blocks) complex_rows += static_cast<long>(b.rows.size());
  // The whitened equations (and instruments), real parts over imaginary parts, kept as tall matrices: QR
  // factorisations of them (instead of normal matrices) keep the condition number from being squared, which a
  // lightly damped resonance (whitening weights 1/(2 zeta) times the others') makes large.
  Eigen::MatrixXd Aw(2 * complex_rows, total), Hw = Eigen::MatrixXd::Zero(2 * complex_rows, total);
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
    // The instruments' motion: the reference model's response to the measured force, free of measurement noise.
    const Eigen::VectorXcd x_model = Eigen::PartialPivLU<Eigen::MatrixXcd>(Zref).solve(rhs);
    Eigen::MatrixXcd A = Eigen::MatrixXcd::Zero(n, total), H = Eigen::MatrixXcd::Zero(n, total);
    Eigen::VectorXcd c0 = Zref * b.x - rhs;
    for (Eigen::Index j = 0; j < k; ++j) {
      const auto js = static_cast<std::size_t>(j);
      const Eigen::MatrixXcd Zj = Z(s.dM[js], s.dC[js], s.dK[js]);
      const Eigen::VectorXcd force_part = pw * (take_rows(s.dB[js], b.rows).cast<cd>() * b.force);
      A.col(j) = Zj * b.x - force_part;
      H.col(j) = Zj * x_model - force_part;
      c0 -= s.p[free[js]] * A.col(j);
    }
    A.col(cconst) = c0;
    if (b.nuisance >= 0)
      for (Eigen::Index l = 0; l < n; ++l) {
        const Eigen::Index col = k + 2 * (b.nuisance * nc + b.rows[static_cast<std::size_t>(l)]);
        A(l, col) = H(l, col) = iw;  // i w a_l
        A(l, col + 1) = H(l, col + 1) = 1;  // b_l
      }
    raw.push_back(A);
    rhs_norm2.push_back(rhs.squaredNorm());
    const Eigen::MatrixXcd W = whiten * A, WH = whiten * H;
    Aw.middleRows(row, n) = W.real();
    Aw.middleRows(row + n, n) = W.imag();
    Hw.middleRows(row, n) = WH.real();
    Hw.middleRows(row + n, n) = WH.imag();
    row += 2 * n;
  }

  // Columns scaled to unit norm. The unknowns in the order: end terms that occur, then the parameters (so that the
  // trailing block of the R factor is the parameters' with the end terms eliminated).
  Eigen::VectorXd D(total);
  for (Eigen::Index j = 0; j < total; ++j) {
    const double norm = Aw.col(j).norm();
    D[j] = norm > 0 ? 1 / norm : 1.0;
  }
  std::vector<int> order;
  Eigen::Index e_used = 0;
  for (Eigen::Index j = k; j < k + E; ++j)
    if (Aw.col(j).squaredNorm() > 0) {
      order.push_back(static_cast<int>(j));
      ++e_used;
    }
  for (Eigen::Index j = 0; j < k; ++j) order.push_back(static_cast<int>(j));
  const auto m = static_cast<Eigen::Index>(order.size());
  if (Aw.rows() < m + 1) throw FitError("fit: --method direct: fewer equations than unknowns");
  Eigen::MatrixXd Au(Aw.rows(), m), Hu(Aw.rows(), m);
  for (Eigen::Index c = 0; c < m; ++c) {
    const int j = order[static_cast<std::size_t>(c)];
    Au.col(c) = Aw.col(j) * D[j];
    Hu.col(c) = Hw.col(j) * D[j];
  }
  const Eigen::VectorXd Ac = Aw.col(cconst);  // the constant column, coefficient 1

  DirectSolution out;
  out.equations = 2 * complex_rows;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Au);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(m).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd Rpp = R.bottomRightCorner(k, k);
  if (k > 0) {
    out.identifiability = analyse_identifiability(Rpp, id_options);
    const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(Rpp).singularValues();
    out.condition = sv[k - 1] > 0 ? sv[0] / sv[k - 1] : std::numeric_limits<double>::infinity();
  }
  const Eigen::VectorXd ls = -qr.solve(Ac);
  Eigen::VectorXd u = ls;
  Eigen::MatrixXd Minv;  // covariance shape of u: lambda/2 Minv Minv^T
  if (instrumental && k > 0) {
    // Instrumental variables: the equations projected on the instruments' span, Q_H^T (A u + a_c) = 0.
    const Eigen::HouseholderQR<Eigen::MatrixXd> qh(Hu);
    const Eigen::MatrixXd Q = qh.householderQ() * Eigen::MatrixXd::Identity(Hu.rows(), m);
    const Eigen::MatrixXd M = Q.transpose() * Au;
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> solver(M);
    if (solver.rank() == m) {
      u = -solver.solve(Q.transpose() * Ac);
      Minv = solver.inverse();
      out.instrumental = true;
    }
  }
  if (!out.instrumental) Minv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(m, m));
  const double rss = (Au * u + Ac).squaredNorm();
  const double dof = double(out.equations) - double(m);
  out.noise_scale = dof > 0 ? 2 * rss / dof : 0;  // per complex equation
  out.equation_rms = complex_rows > 0 ? std::sqrt(rss / double(complex_rows)) : 0;
  out.values = reference;
  out.ls_values = reference;
  for (Eigen::Index j = 0; j < k; ++j) {
    out.values[free[static_cast<std::size_t>(j)]] = D[j] * u[e_used + j];
    out.ls_values[free[static_cast<std::size_t>(j)]] = D[j] * ls[e_used + j];
  }
  if (k > 0) {
    // First order, the whitened equation errors white with variance lambda/2 per real part.
    const Eigen::MatrixXd cu = 0.5 * out.noise_scale * Minv * Minv.transpose();
    const Eigen::VectorXd Dp = D.head(k);
    out.covariance = Dp.asDiagonal() * cu.bottomRightCorner(k, k) * Dp.asDiagonal();
  }
  // Unweighted equation error at the solution.
  Eigen::VectorXd full = Eigen::VectorXd::Zero(total);
  for (Eigen::Index c = 0; c < m; ++c) full[order[static_cast<std::size_t>(c)]] = D[order[static_cast<std::size_t>(c)]] * u[c];
  full[cconst] = 1;
  double e2 = 0, r2 = 0;
  for (std::size_t b = 0; b < raw.size(); ++b) {
    e2 += (raw[b] * full.cast<cd>()).squaredNorm();
    r2 += rhs_norm2[b];
  }
  out.relative_equation_error = r2 > 0 ? std::sqrt(e2 / r2) : 0;
  return out;
}

}  // namespace mbgen::methods
