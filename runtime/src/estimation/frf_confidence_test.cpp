// The delta-method band of an FRF (mbgen/estimation/frf_confidence.hpp) on a one-mass model assembled by hand: its
// standard deviations of |H| and of the phase against finite differences of the exact FRF and against a Monte Carlo
// sample of the parameters drawn with a fixed seed.
#include "mbgen/estimation/frf_confidence.hpp"

#include "mbgen_test/linear_model.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <cstdint>
#include <random>

#include <Eigen/Cholesky>

using namespace mbgen;

namespace {

const double kPi = std::acos(-1.0);

// m q'' + c q' + k q = F, y = q: H = 1 / (k - w^2 m + j w c), written here independently of the runtime.
std::complex<double> receptance(double m, double c, double k, double f_hz) {
  const double w = 2 * kPi * f_hz;
  return 1.0 / std::complex<double>(k - w * w * m, w * c);
}

test::LinearModel one_mass() {
  test::LinearModel model("one_mass", 1, {"F"}, {"y"});
  const int m = model.parameter("m", 2.0, ParameterRole::Estimate);
  const int c = model.parameter("c", 40.0, ParameterRole::Estimate);
  const int k = model.parameter("k", 8e5, ParameterRole::Estimate);
  model.linear(test::LinearModel::M, m, 0, 0, 1);
  model.linear(test::LinearModel::C, c, 0, 0, 1);
  model.linear(test::LinearModel::K, k, 0, 0, 1);
  model.constant(test::LinearModel::B, 0, 0, 1);
  model.constant(test::LinearModel::Cd, 0, 0, 1);
  return model;
}

Eigen::VectorXd gaussian(Eigen::Index n, std::mt19937_64& rng) {
  const auto uniform = [&] { return (static_cast<double>(rng() >> 11) + 0.5) / 9007199254740992.0; };
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = std::sqrt(-2 * std::log(uniform())) * std::cos(2 * kPi * uniform());
  return x;
}

}  // namespace

TEST_CASE("the delta-method std of |H| and of the phase against finite differences and Monte Carlo", "[frf_confidence]") {
  const test::LinearModel model = one_mass();
  Eigen::VectorXd p(3);
  p << 2.0, 40.0, 8e5;  // resonance 100.7 Hz, zeta 0.016
  // Relative stds 0.3 % (m), 2 % (c), 0.2 % (k); m and k correlated +0.6, as a fit's are.
  const Eigen::Vector3d s(0.006, 0.8, 1600);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  R(0, 2) = R(2, 0) = 0.6;
  const Eigen::Matrix3d cov = s.asDiagonal() * R * s.asDiagonal();
  const std::vector<double> f{30, 90, 98, 104, 120, 300};
  const FrfBand band = frf_band(model, p, {0, 1, 2}, cov, f, 0, 0);

  // Finite differences of the exact FRF.
  for (std::size_t l = 0; l < f.size(); ++l) {
    INFO("f = " << f[l]);
    const auto at = [&](const Eigen::VectorXd& q) { return receptance(q[0], q[1], q[2], f[l]); };
    CHECK(std::abs(band.H[static_cast<Eigen::Index>(l)] - at(p)) < 1e-12 * std::abs(at(p)));
    Eigen::Vector3d a, b;
    for (int j = 0; j < 3; ++j) {
      const double h = 1e-6 * p[j];
      Eigen::VectorXd up = p, down = p;
      up[j] += h;
      down[j] -= h;
      a[j] = (std::abs(at(up)) - std::abs(at(down))) / (2 * h);
      b[j] = (std::arg(at(up)) - std::arg(at(down))) / (2 * h) * 180 / kPi;
    }
    CHECK(band.magnitude_std[static_cast<Eigen::Index>(l)] == Approx(std::sqrt(a.dot(cov * a))).epsilon(1e-5));
    CHECK(band.phase_std_deg[static_cast<Eigen::Index>(l)] == Approx(std::sqrt(b.dot(cov * b))).epsilon(1e-5));
  }

  // Monte Carlo: 20000 parameter vectors from N(p, cov) with a fixed seed; the sample std's own relative error is
  // about 1/sqrt(2 x 20000) = 0.5 %, the linearisation's a little more near the peak.
  std::mt19937_64 rng(5);
  const Eigen::Matrix3d L = cov.llt().matrixL();
  const int draws = 20000;
  Eigen::MatrixXd magnitude(draws, static_cast<Eigen::Index>(f.size())), phase(draws, static_cast<Eigen::Index>(f.size()));
  for (int i = 0; i < draws; ++i) {
    const Eigen::VectorXd q = p + L * gaussian(3, rng);
    for (std::size_t l = 0; l < f.size(); ++l) {
      const std::complex<double> h = receptance(q[0], q[1], q[2], f[l]);
      magnitude(i, static_cast<Eigen::Index>(l)) = std::abs(h);
      phase(i, static_cast<Eigen::Index>(l)) = std::arg(h) * 180 / kPi;
    }
  }
  for (std::size_t l = 0; l < f.size(); ++l) {
    INFO("f = " << f[l]);
    const auto col = static_cast<Eigen::Index>(l);
    const auto sample_std = [&](const Eigen::MatrixXd& x) {
      return std::sqrt((x.col(col).array() - x.col(col).mean()).square().sum() / (draws - 1));
    };
    CHECK(band.magnitude_std[col] == Approx(sample_std(magnitude)).epsilon(0.04));
    CHECK(band.phase_std_deg[col] == Approx(sample_std(phase)).epsilon(0.04));
  }
}

TEST_CASE("a parameter held by a data set's `# set` value adds nothing to the band", "[frf_confidence]") {
  const test::LinearModel model = one_mass();
  Eigen::VectorXd p(3);
  p << 2.0, 40.0, 8e5;
  const Eigen::Matrix3d cov = Eigen::Vector3d(0.006 * 0.006, 0, 0).asDiagonal();  // only m uncertain
  const FrfBand free = frf_band(model, p, {0, 1, 2}, cov, {50, 150}, 0, 0);
  const FrfBand held = frf_band(model, p, {0, 1, 2}, cov, {50, 150}, 0, 0, {0});
  CHECK(free.magnitude_std.minCoeff() > 0);
  CHECK(held.magnitude_std.maxCoeff() == 0);
  CHECK(held.phase_std_deg.maxCoeff() == 0);
}

TEST_CASE("several channels' bands at once are each channel's band", "[frf_confidence]") {
  // Two masses in a chain, both displacements measured: channels (0, 0) and (1, 0) from one Jacobian.
  test::LinearModel model("two_masses", 2, {"F"}, {"y1", "y2"});
  const int m = model.parameter("m", 1.5, ParameterRole::Estimate);
  const int k1 = model.parameter("k1", 4e5, ParameterRole::Estimate);
  const int k2 = model.parameter("k2", 2e5, ParameterRole::Estimate);
  model.linear(test::LinearModel::M, m, 0, 0, 1);
  model.linear(test::LinearModel::M, m, 1, 1, 1);
  model.element(test::LinearModel::K, k1, 0, -1);
  model.element(test::LinearModel::K, k2, 0, 1);
  model.constant(test::LinearModel::C, 0, 0, 5);
  model.constant(test::LinearModel::C, 1, 1, 5);
  model.constant(test::LinearModel::B, 0, 0, 1);
  model.constant(test::LinearModel::Cd, 0, 0, 1);
  model.constant(test::LinearModel::Cd, 1, 1, 1);
  Eigen::VectorXd p(3);
  p << 1.5, 4e5, 2e5;
  const Eigen::Matrix3d cov = Eigen::Vector3d(1e-4, 1e6, 4e5).asDiagonal();
  const std::vector<double> f{20, 60, 120, 200};
  const std::vector<FrfBand> both = frf_bands(model, p, {0, 1, 2}, cov, f, {{0, 0}, {1, 0}});
  REQUIRE(both.size() == 2);
  for (int output = 0; output < 2; ++output) {
    const FrfBand one = frf_band(model, p, {0, 1, 2}, cov, f, output, 0);
    CHECK(both[static_cast<std::size_t>(output)].magnitude_std == one.magnitude_std);
    CHECK(both[static_cast<std::size_t>(output)].phase_std_deg == one.phase_std_deg);
    CHECK(both[static_cast<std::size_t>(output)].H == one.H);
  }
  CHECK(both[0].magnitude_std != both[1].magnitude_std);  // two different channels
}
