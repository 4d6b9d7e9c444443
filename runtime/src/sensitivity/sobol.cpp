// Sobol indices by the Saltelli scheme: matrices A and B of N points, and A_B^(i) (A with column i from B).
// First order, Saltelli et al. 2010 (their Table 2, b): S_i = mean(f(B) (f(A_B^i) - f(A))) / V, with f(B) centered.
// Total, Jansen 1999: S_Ti = mean((f(A) - f(A_B^i))^2) / (2 V). V from the 2N points of A and B.
#include "mbgen/sensitivity/sensitivity.hpp"

#include "mbgen/dynamics/parallel.hpp"

#include <cmath>
#include <limits>
#include <random>

namespace mbgen {

namespace {

// Uniform [0, 1) from 53 random bits: the same numbers on every platform (std::uniform_real_distribution is
// implementation-defined).
double unit(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * (1.0 / 9007199254740992.0); }

double mean_and_std_error(const std::vector<double>& terms, double& std_error) {
  double sum = 0;
  for (double t : terms) sum += t;
  const double n = static_cast<double>(terms.size()), mean = sum / n;
  double ss = 0;
  for (double t : terms) ss += (t - mean) * (t - mean);
  std_error = n > 1 ? std::sqrt(ss / (n - 1) / n) : std::numeric_limits<double>::quiet_NaN();
  return mean;
}

}  // namespace

SobolIndices sobol_indices(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, int dimensions, int outputs,
                           const SobolOptions& options) {
  const int n = options.samples, k = dimensions;
  // Points: row j of A, then row j of B, j = 0..N-1, from one generator.
  std::mt19937_64 engine(options.seed);
  Eigen::MatrixXd a(n, k), b(n, k);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < k; ++i) a(j, i) = unit(engine);
    for (int i = 0; i < k; ++i) b(j, i) = unit(engine);
  }
  // Evaluation e = block * N + j: block 0 is A, 1 is B, 2 + i is A_B^(i).
  const int evaluations = n * (k + 2);
  Eigen::MatrixXd y(outputs, evaluations);
  parallel_for(static_cast<std::size_t>(evaluations), options.threads, [&](std::size_t index) {
    const int e = static_cast<int>(index), block = e / n, j = e % n;
    Eigen::VectorXd x = block == 1 ? Eigen::VectorXd(b.row(j).transpose()) : Eigen::VectorXd(a.row(j).transpose());
    if (block >= 2) x[block - 2] = b(j, block - 2);
    const Eigen::VectorXd v = f(x);
    y.col(e) = v.size() == outputs ? v : Eigen::VectorXd::Constant(outputs, std::numeric_limits<double>::quiet_NaN());
  });

  SobolIndices out;
  out.evaluations = evaluations;
  out.first.resize(outputs, k);
  out.total.resize(outputs, k);
  out.first_std.resize(outputs, k);
  out.total_std.resize(outputs, k);
  out.mean.resize(outputs);
  out.variance.resize(outputs);
  out.used.resize(outputs);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int o = 0; o < outputs; ++o) {
    std::vector<int> samples;  // those with every evaluation finite for this output
    for (int j = 0; j < n; ++j) {
      bool finite = true;
      for (int block = 0; block < k + 2 && finite; ++block) finite = std::isfinite(y(o, block * n + j));
      if (finite) samples.push_back(j);
    }
    out.used[o] = static_cast<int>(samples.size());
    double sum = 0, sum2 = 0;
    for (int j : samples)
      for (int block = 0; block < 2; ++block) sum += y(o, block * n + j);
    const double count = 2.0 * static_cast<double>(samples.size());
    const double mean = count > 0 ? sum / count : nan;
    for (int j : samples)
      for (int block = 0; block < 2; ++block) sum2 += std::pow(y(o, block * n + j) - mean, 2);
    const double variance = count > 1 ? sum2 / (count - 1) : nan;
    out.mean[o] = mean;
    out.variance[o] = variance;
    for (int i = 0; i < k; ++i) {
      if (!(variance > 0) || samples.size() < 2) {
        out.first(o, i) = out.total(o, i) = out.first_std(o, i) = out.total_std(o, i) = nan;
        continue;
      }
      std::vector<double> first_terms, total_terms;
      for (int j : samples) {
        const double fa = y(o, j), fb = y(o, n + j), fab = y(o, (2 + i) * n + j);
        // Centered: E[(f(B) - c)(f(A_B) - f(A))] is the same for any constant c, its scatter least for the mean.
        first_terms.push_back((fb - mean) * (fab - fa));
        total_terms.push_back(0.5 * (fa - fab) * (fa - fab));
      }
      double se = 0;
      out.first(o, i) = mean_and_std_error(first_terms, se) / variance;
      out.first_std(o, i) = se / variance;
      out.total(o, i) = mean_and_std_error(total_terms, se) / variance;
      out.total_std(o, i) = se / variance;
    }
  }
  return out;
}

}  // namespace mbgen
