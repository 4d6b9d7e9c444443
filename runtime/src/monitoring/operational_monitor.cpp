// Monitoring in operation: tracked output-only modes, the conditions' effect removed, a Hotelling T^2 chart
// (runtime/include/mbgen/monitoring/operational_monitor.hpp, docs/monitor.md).
#include "mbgen/monitoring/operational_monitor.hpp"

#include "mbgen/monitoring/change_detection.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace mbgen {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  if (a.size() != b.size() || a.size() == 0) return 0;
  const double den = a.squaredNorm() * b.squaredNorm();
  return den > 0 ? std::norm(a.dot(b)) / den : 0.0;
}

// Per tracked mode, the index of the set's mode that continues it, or -1: candidates with at least min_mac and a
// frequency within max_relative_shift, assigned one to one, largest MAC first (ties: the nearer frequency).
std::vector<int> pair_with_tracked(const std::vector<OperationalMode>& tracked, const std::vector<OperationalMode>& modes,
                                   const OperationalMonitorOptions& options, std::vector<double>& macs) {
  struct Candidate {
    double mac, df;
    std::size_t t, m;
  };
  std::vector<Candidate> candidates;
  for (std::size_t t = 0; t < tracked.size(); ++t)
    for (std::size_t m = 0; m < modes.size(); ++m) {
      const double value = mac(tracked[t].shape, modes[m].shape);
      const double df = std::abs(modes[m].f_hz - tracked[t].f_hz) / tracked[t].f_hz;
      if (value >= options.min_mac && df <= options.max_relative_shift) candidates.push_back({value, df, t, m});
    }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.mac != b.mac ? a.mac > b.mac : a.df < b.df;
  });
  std::vector<int> pair(tracked.size(), -1);
  std::vector<bool> used(modes.size(), false);
  macs.assign(tracked.size(), kNaN);
  for (const Candidate& c : candidates) {
    if (pair[c.t] >= 0 || used[c.m]) continue;
    pair[c.t] = static_cast<int>(c.m);
    used[c.m] = true;
    macs[c.t] = c.mac;
  }
  return pair;
}

double student_t_quantile(double p, double nu) {
  double lo = -1e3, hi = 1e3;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * std::max(1.0, std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (student_t_cdf(mid, nu) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::string format(const char* pattern, double a, double b = 0, double c = 0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

// The compensation learnt on the baseline, applied to one set's features x (and its conditions c): the residual
// e, the prediction's leverage h and the T^2.
struct Compensator {
  Compensation kind = Compensation::Regression;
  // Regression (and none, with no regressors): Z = [1, c - cbar]
  Eigen::VectorXd cbar;
  Eigen::MatrixXd gram_inverse, coefficients, residual_cov, residual_cov_inverse;
  // Principal components
  Eigen::VectorXd mean;
  Eigen::MatrixXd leading, minor;  // p x r, p x m (unit columns)
  Eigen::VectorXd leading_var, minor_var;  // minor: rescaled to nu degrees of freedom
  int baseline = 0;
};

struct Applied {
  Eigen::VectorXd residual, prediction, sigma;
  double leverage = 0, t2 = 0;
};

Applied apply(const Compensator& m, const Eigen::VectorXd& x, const Eigen::VectorXd& c) {
  Applied a;
  if (m.kind != Compensation::PrincipalComponents) {
    Eigen::VectorXd z(1 + m.cbar.size());
    z[0] = 1;
    if (m.kind == Compensation::Regression) z.tail(m.cbar.size()) = c - m.cbar;  // none: the conditions unused
    a.prediction = m.coefficients.transpose() * z;
    a.leverage = z.dot(m.gram_inverse * z);
    a.residual = x - a.prediction;
    a.t2 = a.residual.dot(m.residual_cov_inverse * a.residual) / (1 + a.leverage);
    a.sigma = (m.residual_cov.diagonal() * (1 + a.leverage)).cwiseSqrt();
    return a;
  }
  const Eigen::VectorXd d = x - m.mean;
  const Eigen::VectorXd s = m.leading.transpose() * d;
  a.leverage = 1.0 / m.baseline;
  for (Eigen::Index k = 0; k < s.size(); ++k) a.leverage += s[k] * s[k] / ((m.baseline - 1) * m.leading_var[k]);
  const Eigen::VectorXd y = m.minor.transpose() * d;
  a.residual = m.minor * y;
  a.prediction = x - a.residual;
  a.t2 = y.cwiseAbs2().cwiseQuotient(m.minor_var).sum() / (1 + a.leverage);
  a.sigma = (m.minor.cwiseAbs2() * m.minor_var * (1 + a.leverage)).cwiseSqrt();
  return a;
}

}  // namespace

const char* compensation_name(Compensation c) {
  switch (c) {
    case Compensation::Regression: return "regression";
    case Compensation::PrincipalComponents: return "principal components";
    case Compensation::None: break;
  }
  return "none";
}

double f_distribution_cdf(double x, double d1, double d2) {
  if (!(x > 0)) return 0;
  return regularized_incomplete_beta(d1 / 2, d2 / 2, d1 * x / (d1 * x + d2));
}

double f_distribution_quantile(double p, double d1, double d2) {
  if (!(p > 0) || !(p < 1) || !(d1 > 0) || !(d2 > 0))
    throw std::invalid_argument("f_distribution_quantile: p in (0, 1) and positive degrees of freedom");
  double lo = 0, hi = 1;
  while (f_distribution_cdf(hi, d1, d2) < p && hi < 1e300) hi *= 2;
  for (int i = 0; i < 400 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f_distribution_cdf(mid, d1, d2) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double hotelling_limit(int p, int nu, double alpha) {
  if (p < 1 || nu < p) throw std::invalid_argument("hotelling_limit: needs nu >= p >= 1");
  const double d2 = nu - p + 1;
  return static_cast<double>(nu) * p / d2 * f_distribution_quantile(1 - alpha, p, d2);
}

OperationalMonitorResult monitor_operational(const std::vector<OperationalSet>& sets,
                                             const std::vector<std::string>& condition_names,
                                             const OperationalMonitorOptions& options) {
  const int n = static_cast<int>(sets.size());
  const int q = static_cast<int>(condition_names.size());
  const int K = options.baseline > 0 ? options.baseline : n / 2;
  if (n <= K || K < 2)
    throw std::invalid_argument("monitoring needs more data sets (" + std::to_string(n) + ") than the baseline's " +
                                std::to_string(K) + ", and a baseline of at least 2");
  if (!(options.false_alarm > 0 && options.false_alarm < 1))
    throw std::invalid_argument("the false-alarm probability must lie in (0, 1)");
  const std::vector<OperationalMode>& reference = sets.front().modes;
  if (reference.empty()) throw std::invalid_argument(sets.front().file + ": no mode was identified in the first set");

  // Pair every set's modes with the first set's; keep the modes found in every baseline set.
  std::vector<std::vector<int>> pairs(static_cast<std::size_t>(n));
  std::vector<std::vector<double>> macs(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    pairs[i] = pair_with_tracked(reference, sets[i].modes, options, macs[i]);
  std::vector<std::size_t> keep;
  for (std::size_t t = 0; t < reference.size(); ++t) {
    bool everywhere = true;
    for (int i = 0; i < K; ++i) everywhere = everywhere && pairs[i][t] >= 0;
    if (everywhere) keep.push_back(t);
  }
  if (keep.empty())
    throw std::invalid_argument("no mode of the first set was found in every baseline set (MAC >= " +
                                format("%g", options.min_mac) + ", frequency within " +
                                format("%g", 100 * options.max_relative_shift) + " %)");
  const int p = static_cast<int>(keep.size());
  // Features: per set, the tracked modes' frequencies (NaN where not found).
  Eigen::MatrixXd F(n, p), Z(n, p), M(n, p);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < p; ++j) {
      const int m = pairs[i][keep[static_cast<std::size_t>(j)]];
      F(i, j) = m >= 0 ? sets[i].modes[static_cast<std::size_t>(m)].f_hz : kNaN;
      Z(i, j) = m >= 0 ? sets[i].modes[static_cast<std::size_t>(m)].zeta : kNaN;
      M(i, j) = macs[i][keep[static_cast<std::size_t>(j)]];
    }
  Eigen::MatrixXd C(n, q);
  for (int i = 0; i < n; ++i) {
    if (static_cast<int>(sets[i].conditions.size()) != q)
      throw std::invalid_argument(sets[i].file + ": its conditions do not match the condition names");
    for (int k = 0; k < q; ++k) C(i, k) = sets[i].conditions[static_cast<std::size_t>(k)];
  }

  OperationalMonitorResult r;
  r.conditions = condition_names;
  r.baseline = K;
  r.false_alarm = options.false_alarm;
  r.compensation = !options.compensate ? Compensation::None
                   : q > 0            ? Compensation::Regression
                                      : Compensation::PrincipalComponents;
  const Eigen::MatrixXd X = F.topRows(K);
  for (int j = 0; j < p; ++j) {
    TrackedMode t;
    t.f_hz = X.col(j).mean();
    t.zeta = Z.col(j).head(K).mean();
    t.f_std_hz = std::sqrt((X.col(j).array() - t.f_hz).square().sum() / (K - 1));
    t.shape = reference[keep[static_cast<std::size_t>(j)]].shape;
    r.modes.push_back(std::move(t));
  }

  Compensator model;
  model.kind = r.compensation;
  model.baseline = K;
  int features = p;
  if (r.compensation != Compensation::PrincipalComponents) {
    const int regressors = r.compensation == Compensation::Regression ? q : 0;
    if (K < p + regressors + 1)
      throw std::invalid_argument("the baseline (" + std::to_string(K) + " sets) is too small for " +
                                  std::to_string(p) + " tracked modes and " + std::to_string(regressors) +
                                  " condition variables: it needs at least " + std::to_string(p + regressors + 1));
    model.cbar = regressors ? Eigen::VectorXd(C.topRows(K).colwise().mean().transpose()) : Eigen::VectorXd(0);
    Eigen::MatrixXd design(K, 1 + regressors);
    design.col(0).setOnes();
    for (int k = 0; k < regressors; ++k) design.col(1 + k) = C.col(k).head(K).array() - model.cbar[k];
    const Eigen::MatrixXd gram = design.transpose() * design;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(gram);
    for (int k = 0; k < regressors; ++k)
      if (design.col(1 + k).cwiseAbs().maxCoeff() == 0)
        throw std::invalid_argument("the condition '" + condition_names[static_cast<std::size_t>(k)] +
                                    "' is constant over the baseline: its effect cannot be learnt");
    if (!lu.isInvertible())
      throw std::invalid_argument("the conditions are linearly dependent over the baseline: their effects cannot "
                                  "be told apart");
    model.gram_inverse = lu.inverse();
    model.coefficients = model.gram_inverse * design.transpose() * X;
    const Eigen::MatrixXd E = X - design * model.coefficients;
    r.dof = K - regressors - 1;
    model.residual_cov = E.transpose() * E / r.dof;
    Eigen::FullPivLU<Eigen::MatrixXd> cov(model.residual_cov);
    if (!cov.isInvertible())
      throw std::invalid_argument("the baseline's compensated frequencies have a singular covariance (a mode's "
                                  "frequency identical in every set?)");
    model.residual_cov_inverse = cov.inverse();
    for (int j = 0; j < p; ++j) {
      std::vector<double> per_condition;
      for (int k = 0; k < regressors; ++k) per_condition.push_back(model.coefficients(1 + k, j));
      r.effects.push_back(per_condition);
      r.residual_std_hz.push_back(std::sqrt(model.residual_cov(j, j)));
    }
    r.shift_projector = Eigen::MatrixXd::Identity(p, p);
  } else {
    if (p < 2)
      throw std::invalid_argument("one tracked mode and no condition variables: a principal-component model needs "
                                  "at least two modes (or give `# condition` lines)");
    model.mean = X.colwise().mean().transpose();
    const Eigen::MatrixXd Xc = X.rowwise() - model.mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Xc.transpose() * Xc / (K - 1));
    // Descending order; each direction's sign fixed (largest component positive) so that output is reproducible.
    Eigen::VectorXd values = eig.eigenvalues().reverse();
    Eigen::MatrixXd vectors = eig.eigenvectors().rowwise().reverse();
    for (int k = 0; k < p; ++k) {
      Eigen::Index big;
      vectors.col(k).cwiseAbs().maxCoeff(&big);
      if (vectors(big, k) < 0) vectors.col(k) *= -1;
    }
    const double total = values.sum();
    for (int k = 0; k < p; ++k) r.component_variance.push_back(total > 0 ? values[k] / total : kNaN);
    int lead = options.environmental_components;
    if (lead < 0) {
      lead = 0;
      double covered = 0;
      while (lead < p - 1 && covered < options.environmental_variance) covered += r.component_variance[lead++];
    }
    if (lead > p - 1)
      throw std::invalid_argument("at most " + std::to_string(p - 1) + " environmental components with " +
                                  std::to_string(p) + " tracked modes");
    features = p - lead;
    r.environmental_components = lead;
    r.dof = K - 1 - lead;
    if (r.dof < features)
      throw std::invalid_argument("the baseline (" + std::to_string(K) + " sets) is too small for " +
                                  std::to_string(p) + " tracked modes: it needs at least " + std::to_string(p + 1));
    model.leading = vectors.leftCols(lead);
    model.leading_var = values.head(lead);
    model.minor = vectors.rightCols(features);
    // The minor components' variance on the residuals' own degrees of freedom (the leading ones used up `lead`).
    model.minor_var = values.tail(features) * (K - 1.0) / r.dof;
    if (!(model.minor_var.minCoeff() > 0))
      throw std::invalid_argument("the baseline's frequencies leave no scatter outside the environmental components");
    for (int k = 0; k < lead; ++k) r.effects.emplace_back(vectors.col(k).data(), vectors.col(k).data() + p);
    const Eigen::VectorXd var = model.minor.cwiseAbs2() * model.minor_var;
    for (int j = 0; j < p; ++j) r.residual_std_hz.push_back(std::sqrt(var[j]));
    r.shift_projector = model.minor * model.minor.transpose();
  }
  r.features = features;
  r.limit = hotelling_limit(features, r.dof, options.false_alarm);
  r.mode_limit = student_t_quantile(1 - options.false_alarm / (2 * features), r.dof);

  for (int i = 0; i < n; ++i) {
    OperationalPoint s;
    s.file = sets[i].file;
    s.time = sets[i].time;
    s.conditions = sets[i].conditions;
    s.baseline = i < K;
    s.identified = static_cast<int>(sets[i].modes.size());
    for (int j = 0; j < p; ++j) {
      s.f_hz.push_back(F(i, j));
      s.zeta.push_back(Z(i, j));
      s.mac.push_back(M(i, j));
    }
    s.compensated_hz = s.shift_percent = s.shift_sigma = std::vector<double>(static_cast<std::size_t>(p), kNaN);
    s.t2 = s.leverage = kNaN;
    if (F.row(i).allFinite()) {
      const Applied a = apply(model, F.row(i).transpose(), C.row(i).transpose());
      s.leverage = a.leverage;
      s.t2 = a.t2;
      for (int j = 0; j < p; ++j) {
        s.compensated_hz[j] = r.modes[j].f_hz + a.residual[j];
        s.shift_percent[j] = 100 * a.residual[j] / a.prediction[j];
        s.shift_sigma[j] = a.sigma[j] > 0 ? a.residual[j] / a.sigma[j] : kNaN;
      }
      if (model.kind != Compensation::PrincipalComponents)  // the compensated level is at the baseline's mean
        for (int j = 0; j < p; ++j)
          s.compensated_hz[j] = model.coefficients(0, j) + a.residual[j];
      s.alarm = !s.baseline && s.t2 > r.limit;
    }
    r.series.push_back(std::move(s));
  }

  // Runs of alarms: a change starts at the first set of each.
  for (int i = K; i < n; ++i) {
    if (!r.series[i].alarm || (i > K && r.series[i - 1].alarm)) continue;
    OperationalChange c;
    c.index = c.last = i;
    while (c.last + 1 < n && r.series[c.last + 1].alarm) ++c.last;
    const OperationalPoint& s = r.series[i];
    c.shift_percent = s.shift_percent;
    c.shift_sigma = s.shift_sigma;
    for (int j = 0; j < p; ++j)
      if (std::abs(s.shift_sigma[j]) > r.mode_limit) c.modes.push_back(j);
    c.text = "T^2 " + format("%.4g", s.t2) + " above the limit " + format("%.4g", r.limit) + " from data set " +
             std::to_string(i) + (c.last > i ? " to " + std::to_string(c.last) : "") + "; ";
    if (c.modes.empty()) c.text += "no single mode's shift stands out on its own";
    for (std::size_t k = 0; k < c.modes.size(); ++k) {
      const int j = c.modes[k];
      c.text += (k ? ", " : "moved: ") + std::string("mode ") + std::to_string(j + 1) + " (" +
                format("%.5g Hz", r.modes[j].f_hz) + ") " + format("%+.3g %%", s.shift_percent[j]) + " (" +
                format("%+.3g sigma", s.shift_sigma[j]) + ")";
    }
    r.changes.push_back(std::move(c));
  }
  return r;
}

}  // namespace mbgen
