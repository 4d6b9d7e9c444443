#include "model_coefficients.hpp"

#include "estimation/excited_block.hpp"
#include "mbgen/dynamics/dynamics_error.hpp"
#include "mbgen/dynamics/state_space.hpp"
#include "mbgen/transfer_function.hpp"
#include "polynomial.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <limits>

#include <cmath>

namespace mbgen::methods {

namespace {

Eigen::VectorXd to_vector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

void add_entries(const std::vector<DerivativeEntry>& entries, std::vector<Eigen::MatrixXd>& out, Eigen::Index rows,
                 Eigen::Index cols) {
  for (auto& m : out)
    if (m.size() == 0) m = Eigen::MatrixXd::Zero(rows, cols);
  for (const auto& e : entries) out[static_cast<std::size_t>(e.param)](e.row, e.col) += e.value;
}

}  // namespace

ModelTf model_tf(const Model& model, const Eigen::VectorXd& values, int input, const std::vector<int>& outputs,
                 const std::vector<int>& free) {
  ModelMatrices m;
  model.evaluate(values, m);
  ModelDerivatives d;
  std::vector<int> column(model.info().parameters.size(), -1);
  for (std::size_t j = 0; j < free.size(); ++j) column[static_cast<std::size_t>(free[j])] = static_cast<int>(j);
  if (!free.empty()) model.derivatives(values, d);
  const estimation::ReducedModel r =
      estimation::reduce_to_excited_block(m, free.empty() ? nullptr : &d, {input}, outputs, column);
  const Eigen::Index nb = r.m.M.rows();
  std::vector<int> block(static_cast<std::size_t>(nb));
  for (Eigen::Index i = 0; i < nb; ++i) block[static_cast<std::size_t>(i)] = static_cast<int>(i);

  // Derivative matrices per free parameter, dense.
  const std::size_t nf = free.size();
  std::vector<Eigen::MatrixXd> dM(nf), dC(nf), dK(nf), dB(nf), dCd(nf), dCv(nf), dCa(nf);
  if (nf) {
    add_entries(r.d.M, dM, nb, nb);
    add_entries(r.d.C, dC, nb, nb);
    add_entries(r.d.K, dK, nb, nb);
    add_entries(r.d.B, dB, nb, r.m.B.cols());
    add_entries(r.d.Cd, dCd, r.m.Cd.rows(), nb);
    add_entries(r.d.Cv, dCv, r.m.Cv.rows(), nb);
    add_entries(r.d.Ca, dCa, r.m.Ca.rows(), nb);
  }
  ModelTf out;
  out.block_size = static_cast<int>(nb);
  for (std::size_t c = 0; c < outputs.size(); ++c) {
    const Eigen::Index row = static_cast<Eigen::Index>(c);
    TransferFunctionSystem<double> sys{r.m.M, r.m.C, r.m.K, r.m.Cd.row(row), r.m.Cv.row(row), r.m.Ca.row(row),
                                       r.m.B.col(0)};
    const TransferFunctionCoefficients<double> tf = transfer_function_coefficients(sys, block);
    if (c == 0) out.denominator = to_vector(tf.denominator);
    out.numerators.push_back(to_vector(tf.numerator));
    if (!nf) continue;
    std::vector<TransferFunctionSystem<double>> ds;
    for (std::size_t j = 0; j < nf; ++j)
      ds.push_back({dM[j], dC[j], dK[j], dCd[j].row(row), dCv[j].row(row), dCa[j].row(row), dB[j].col(0)});
    const TransferFunctionJacobian<double> jac = transfer_function_jacobian(sys, ds, block);
    Eigen::MatrixXd dn(2 * nb + 1, static_cast<Eigen::Index>(nf)), dd(2 * nb + 1, static_cast<Eigen::Index>(nf));
    for (std::size_t j = 0; j < nf; ++j) {
      dn.col(static_cast<Eigen::Index>(j)) = to_vector(jac.numerator[j]);
      dd.col(static_cast<Eigen::Index>(j)) = to_vector(jac.denominator[j]);
    }
    if (c == 0) out.ddenominator = dd;
    out.dnumerators.push_back(dn);
  }
  return out;
}

std::vector<std::vector<bool>> structural_pattern(const Model& model, const Eigen::VectorXd& prior, int input,
                                                  const std::vector<int>& outputs, const std::vector<int>& perturbed) {
  std::vector<std::vector<bool>> pattern;
  for (double factor : {0.0, 0.07, -0.11}) {
    Eigen::VectorXd v = prior;
    for (int i : perturbed) v[i] *= 1 + factor;
    const ModelTf tf = model_tf(model, v, input, outputs, {});
    const int q = 2 * tf.block_size;
    // The scale omega0 = a_0^(1/q) puts the coefficients of s / omega0 on a common footing.
    const double a0 = std::abs(tf.denominator[0]);
    const double w0 = a0 > 0 ? std::pow(a0, 1.0 / q) : 1.0;
    std::vector<Eigen::VectorXd> polys = {tf.denominator};
    polys.insert(polys.end(), tf.numerators.begin(), tf.numerators.end());
    if (pattern.empty())
      for (const auto& p : polys) pattern.emplace_back(static_cast<std::size_t>(p.size()), false);
    for (std::size_t k = 0; k < polys.size(); ++k) {
      Eigen::VectorXd scaled = polys[k];
      for (Eigen::Index j = 0; j < scaled.size(); ++j) scaled[j] *= std::pow(w0, double(j - q));
      const double largest = scaled.cwiseAbs().maxCoeff();
      for (Eigen::Index j = 0; j < scaled.size(); ++j)
        if (std::abs(scaled[j]) > 1e-9 * largest) pattern[k][static_cast<std::size_t>(j)] = true;
    }
  }
  return pattern;
}

namespace {

struct Truncated {
  std::vector<std::complex<double>> kept;  // the model modes taken, in the order of `modes`
  Eigen::VectorXd denominator;
  std::vector<Eigen::VectorXd> numerators;
};

Truncated truncate(const Model& model, const Eigen::VectorXd& values, int input, const std::vector<int>& outputs,
                   const std::vector<std::complex<double>>& modes) {
  ModelMatrices m;
  model.evaluate(values, m);
  const estimation::ReducedModel r = estimation::reduce_to_excited_block(m, nullptr, {input}, outputs, {});
  const StateSpace ss = state_space(r.m);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(ss.A);
  const Eigen::VectorXcd lambda = es.eigenvalues();
  const Eigen::MatrixXcd V = es.eigenvectors();
  const Eigen::MatrixXcd Vi = V.inverse();
  const Eigen::MatrixXcd CV = ss.C.cast<std::complex<double>>() * V;
  const Eigen::VectorXcd ViB = Vi * ss.B.col(0).cast<std::complex<double>>();
  // Greedy assignment, nearest pairs first.
  struct Pair {
    double distance;
    std::size_t mode;
    Eigen::Index eigen;
  };
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < modes.size(); ++i)
    for (Eigen::Index j = 0; j < lambda.size(); ++j)
      if (lambda[j].imag() > 0) pairs.push_back({std::abs(lambda[j] - modes[i]) / std::abs(modes[i]), i, j});
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.distance < b.distance; });
  std::vector<Eigen::Index> taken(modes.size(), -1);
  std::vector<bool> used(static_cast<std::size_t>(lambda.size()), false);
  for (const Pair& p : pairs)
    if (taken[p.mode] < 0 && !used[static_cast<std::size_t>(p.eigen)]) {
      taken[p.mode] = p.eigen;
      used[static_cast<std::size_t>(p.eigen)] = true;
    }
  Truncated out;
  for (Eigen::Index j : taken) {
    // At some parameter values (a trial step's): the model's failure there, as a singular mass matrix is, so that
    // the searches take it for a failed trial (a std::logic_error is a bug, and they let it through).
    if (j < 0) throw DynamicsError("the model has fewer vibration modes than the data show");
    out.kept.push_back(lambda[j]);
  }
  const ModalPolynomials mp = modal_polynomials(out.kept);
  out.denominator = mp.denominator;
  const Eigen::Index q = mp.denominator.size() - 1;
  for (std::size_t c = 0; c < outputs.size(); ++c) {
    Eigen::VectorXd rho(q);
    for (std::size_t k = 0; k < taken.size(); ++k) {
      const std::complex<double> res = CV(static_cast<Eigen::Index>(c), taken[k]) * ViB[taken[k]];
      rho[2 * static_cast<Eigen::Index>(k)] = res.real();
      rho[2 * static_cast<Eigen::Index>(k) + 1] = res.imag();
    }
    Eigen::VectorXd num = ss.D(static_cast<Eigen::Index>(c), 0) * mp.denominator;
    num.head(q) += mp.residue_map * rho;
    out.numerators.push_back(num);
  }
  return out;
}

}  // namespace

ModelTf model_tf_truncated(const Model& model, const Eigen::VectorXd& values, int input, const std::vector<int>& outputs,
                           const std::vector<std::complex<double>>& modes, const std::vector<int>& free) {
  const Truncated base = truncate(model, values, input, outputs, modes);
  ModelTf out;
  out.block_size = static_cast<int>(modes.size());
  out.denominator = base.denominator;
  out.numerators = base.numerators;
  if (free.empty()) return out;
  const Eigen::Index nf = static_cast<Eigen::Index>(free.size()), len = base.denominator.size();
  out.ddenominator.resize(len, nf);
  out.dnumerators.assign(outputs.size(), Eigen::MatrixXd(len, nf));
  for (Eigen::Index j = 0; j < nf; ++j) {
    const int p = free[static_cast<std::size_t>(j)];
    const double h = 1e-6 * std::max(std::abs(values[p]), std::numeric_limits<double>::min() * 1e10);
    Eigen::VectorXd plus = values, minus = values;
    plus[p] += h;
    minus[p] -= h;
    // The perturbed models' modes are taken nearest the base model's, so that both sides keep the same modes.
    const Truncated tp = truncate(model, plus, input, outputs, base.kept), tm = truncate(model, minus, input, outputs, base.kept);
    out.ddenominator.col(j) = (tp.denominator - tm.denominator) / (2 * h);
    for (std::size_t c = 0; c < outputs.size(); ++c) out.dnumerators[c].col(j) = (tp.numerators[c] - tm.numerators[c]) / (2 * h);
  }
  return out;
}

}  // namespace mbgen::methods
