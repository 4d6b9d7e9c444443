// Sobol indices of mdof2's modes against brute force: the variance of the conditional mean, by a double loop.
#include "mbgen/sensitivity/sensitivity.hpp"
#include "mbgen_test/mdof2.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

namespace mbgen {
namespace {

double unit(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * (1.0 / 9007199254740992.0); }

}  // namespace

TEST_CASE("slow: Sobol indices of mdof2's frequencies agree with brute force", "[sensitivity][sobol][slow]") {
  const test::Mdof2Model model;
  const Eigen::VectorXd p = model.info().default_values();
  const std::vector<ParameterRange> ranges = parameter_ranges(model.info(), p, 0.2, false);
  REQUIRE(ranges.size() == 7);  // the estimate parameters; c12 is fixed
  CHECK(ranges[0].name == "m1");
  CHECK(ranges[0].lo == Approx(0.8 * 1.39));
  SobolOptions options;
  options.samples = 4096;
  const GlobalSensitivity g = global_sensitivity(model, p, ranges, options);
  REQUIRE(g.nominal.size() == 2);

  // Brute force, independent of the estimators: S_i = Var(E[f | x_i]) / Var(f) with the inner mean over `inner`
  // samples of the other parameters at each of `outer` values of x_i; the inner means' own scatter is subtracted
  // (E[Var_inner] / inner), which makes the estimate unbiased.
  const int outer = 48, inner = 96;
  std::mt19937_64 engine(11);
  const auto frequencies = [&](const Eigen::VectorXd& u) {
    Eigen::VectorXd q = p;
    for (std::size_t i = 0; i < ranges.size(); ++i)
      q[ranges[i].index] = ranges[i].lo + u[static_cast<Eigen::Index>(i)] * (ranges[i].hi - ranges[i].lo);
    const std::vector<Mode> modes = oscillating_modes(model, q);
    const std::vector<int> match = track_modes(g.nominal, modes);
    return Eigen::Vector2d(modes[static_cast<std::size_t>(match[0])].f_hz,
                           modes[static_cast<std::size_t>(match[1])].f_hz);
  };
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    Eigen::MatrixXd means(outer, 2);
    Eigen::Vector2d within = Eigen::Vector2d::Zero(), sum = Eigen::Vector2d::Zero(), sum2 = Eigen::Vector2d::Zero();
    for (int o = 0; o < outer; ++o) {
      const double xi = (o + 0.5) / outer;  // stratified: one value per stratum
      Eigen::MatrixXd y(inner, 2);
      for (int j = 0; j < inner; ++j) {
        Eigen::VectorXd u(static_cast<Eigen::Index>(ranges.size()));
        for (Eigen::Index k = 0; k < u.size(); ++k) u[k] = unit(engine);
        u[static_cast<Eigen::Index>(i)] = xi;
        y.row(j) = frequencies(u).transpose();
        sum += y.row(j).transpose();
        sum2 += y.row(j).transpose().cwiseAbs2();
      }
      means.row(o) = y.colwise().mean();
      within += ((y.rowwise() - means.row(o)).colwise().squaredNorm() / (inner - 1)).transpose();
    }
    const double total_n = static_cast<double>(outer) * inner;
    const Eigen::Vector2d variance = (sum2 - sum.cwiseAbs2() / total_n) / (total_n - 1);
    for (int r = 0; r < 2; ++r) {
      const double mean_of_means = means.col(r).mean();
      const double var_means = (means.col(r).array() - mean_of_means).square().sum() / (outer - 1);
      const double brute = (var_means - within[r] / outer / inner) / variance[r];
      const Eigen::Index ii = static_cast<Eigen::Index>(i);
      INFO(ranges[i].name << ", mode " << r << ": Saltelli " << g.f.first(r, ii) << " +- " << g.f.first_std(r, ii)
                          << ", brute force " << brute);
      // The brute-force estimate's own error is about 0.02 here (48 outer values: the variance of a variance);
      // together with the estimator's standard error.
      CHECK(std::abs(g.f.first(r, ii) - brute) < 0.03 + 4 * g.f.first_std(r, ii));
      // Total >= first order (up to the estimators' errors): mdof2's frequencies are nearly additive here.
      CHECK(g.f.total(r, ii) >= g.f.first(r, ii) - 4 * (g.f.total_std(r, ii) + g.f.first_std(r, ii)));
    }
  }
  // Every sample's modes were matched.
  CHECK(g.f.used[0] == 4096);
  CHECK(g.zeta.used[1] == 4096);
}

}  // namespace mbgen
