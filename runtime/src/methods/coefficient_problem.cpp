#include "coefficient_problem.hpp"

#include "model_coefficients.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace mbgen::methods {

CoefficientProblem::CoefficientProblem(const Model& model, const std::vector<StepOneTf>& tfs) : model_(model), tfs_(tfs) {
  for (std::size_t t = 0; t < tfs.size(); ++t) {
    const StepOneTf& s = tfs[t];
    const int q = s.tf.order();
    for (int j = 0; j < q; ++j)
      if (s.pattern[0][static_cast<std::size_t>(j)] && s.tf.denominator[j] != 0) targets_.push_back({t, -1, j, s.tf.denominator[j], j});
    for (std::size_t c = 0; c < s.tf.numerators.size(); ++c)
      for (Eigen::Index j = 0; j < s.tf.numerators[c].size(); ++j)
        if (s.pattern[1 + c][static_cast<std::size_t>(j)] && s.tf.numerators[c][j] != 0)
          targets_.push_back({t, static_cast<int>(c), static_cast<int>(j), s.tf.numerators[c][j],
                              s.tf.numerator_index(c, static_cast<int>(j))});
  }
}

void CoefficientProblem::evaluate(const Eigen::VectorXd& values, const std::vector<int>& free, Eigen::VectorXd& r,
                                  Eigen::MatrixXd* J, Eigen::VectorXd* model_values) const {
  const Eigen::Index n = static_cast<Eigen::Index>(targets_.size());
  r.resize(n);
  if (J) J->setZero(n, static_cast<Eigen::Index>(free.size()));
  if (model_values) model_values->resize(n);
  std::size_t current = tfs_.size();
  ModelTf mt;
  for (Eigen::Index i = 0; i < n; ++i) {
    const CoefficientTarget& t = targets_[static_cast<std::size_t>(i)];
    if (t.tf != current) {
      current = t.tf;
      const StepOneTf& s = tfs_[t.tf];
      Eigen::VectorXd v = values;
      for (const auto& [p, value] : s.overrides) v[p] = value;
      const std::vector<int> wrt = J ? free : std::vector<int>{};
      mt = s.truncated_to.empty() ? model_tf(model_, v, s.input, s.outputs, wrt)
                                  : model_tf_truncated(model_, v, s.input, s.outputs, s.truncated_to, wrt);
      // A parameter a `# set` line fixes for this data set does not move its coefficients.
      if (J)
        for (const auto& [p, value] : s.overrides) {
          const auto it = std::find(free.begin(), free.end(), p);
          if (it == free.end()) continue;
          const Eigen::Index j = it - free.begin();
          mt.ddenominator.col(j).setZero();
          for (auto& d : mt.dnumerators) d.col(j).setZero();
        }
    }
    const double model = t.channel < 0 ? mt.denominator[t.power] : mt.numerators[static_cast<std::size_t>(t.channel)][t.power];
    const double scale = 1 / std::abs(t.value);
    r[i] = (model - t.value) * scale;
    if (model_values) (*model_values)[i] = model;
    if (J)
      J->row(i) = (t.channel < 0 ? mt.ddenominator.row(t.power)
                                 : mt.dnumerators[static_cast<std::size_t>(t.channel)].row(t.power)) * scale;
  }
  if (whitening_.size()) {
    r = whitening_ * r;
    if (J) *J = whitening_ * *J;
  }
}

Eigen::MatrixXd CoefficientProblem::weight() const {
  const Eigen::Index n = static_cast<Eigen::Index>(targets_.size());
  Eigen::VectorXd d(n);
  for (Eigen::Index i = 0; i < n; ++i) d[i] = 1 / std::abs(targets_[static_cast<std::size_t>(i)].value);
  if (whitening_.size()) return whitening_ * d.asDiagonal();
  return d.asDiagonal();
}

bool CoefficientProblem::use_covariance_weighting() {
  const Eigen::MatrixXd cov = identified_covariance();
  if (cov.size() == 0) return false;
  whitening_.resize(0, 0);
  const Eigen::MatrixXd D = weight();
  // S^(-1/2) U^T of the normalised covariance D cov D = U S U^T; directions with no variance (relative 1e-14) are
  // left out (they would get infinite weight).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(D * cov * D);
  const Eigen::VectorXd s = es.eigenvalues();
  const double top = s.maxCoeff();
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < s.size(); ++i)
    if (s[i] > top * 1e-14) keep.push_back(i);
  whitening_.resize(static_cast<Eigen::Index>(keep.size()), s.size());
  for (std::size_t k = 0; k < keep.size(); ++k)
    whitening_.row(static_cast<Eigen::Index>(k)) = es.eigenvectors().col(keep[k]).transpose() / std::sqrt(s[keep[k]]);
  return true;
}

Eigen::MatrixXd CoefficientProblem::identified_covariance() const {
  for (const auto& s : tfs_)
    if (s.tf.covariance.size() == 0) return {};
  const Eigen::Index n = static_cast<Eigen::Index>(targets_.size());
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b) {
      const CoefficientTarget &ta = targets_[static_cast<std::size_t>(a)], &tb = targets_[static_cast<std::size_t>(b)];
      if (ta.tf == tb.tf) cov(a, b) = tfs_[ta.tf].tf.covariance(ta.stacked, tb.stacked);
    }
  return cov;
}

}  // namespace mbgen::methods
