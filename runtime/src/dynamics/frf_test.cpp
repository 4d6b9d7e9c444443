#include "mbgen/dynamics/frf.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"
#include "mbgen_test/mdof2.hpp"
#include "mbgen_test/random_affine_model.hpp"
#include "mbgen_test/finite_difference.hpp"

#include <catch2/catch.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <limits>
#include <random>
#include <tuple>

#include <cmath>

namespace {

using cd = std::complex<double>;
const double pi = std::acos(-1.0);

std::vector<double> test_frequencies() {
  // Spread over the band, including points close to both modes (89.72 Hz, 166.29 Hz) and 0 Hz.
  return {0.0, 1.0, 30.0, 89.0, 89.72, 89.8, 120.0, 166.0, 166.29, 170.0, 400.0, 2000.0};
}

}  // namespace

TEST_CASE("mdof2 FRF matches the closed-form polynomial ratio") {
  const mbgen::test::Mdof2Model model(/*extra_outputs=*/true);
  const auto freqs = test_frequencies();
  const auto result = mbgen::frf(model, model.info().default_values(), freqs);
  REQUIRE(result.H.size() == freqs.size());
  const mbgen::test::Mdof2Values v;  // the closed form of docs/reference-models.md
  for (std::size_t k = 0; k < freqs.size(); ++k) {
    const cd s(0, 2 * pi * freqs[k]);
    const cd g11 = mbgen::test::mdof2_g11(v, freqs[k]), g21 = mbgen::test::mdof2_g21(v, freqs[k]);
    const Eigen::MatrixXcd& H = result.H[k];
    REQUIRE(H.rows() == 4);
    REQUIRE(H.cols() == 1);
    INFO("f = " << freqs[k] << " Hz");
    CHECK(std::abs(H(0, 0) - g11) <= 1e-10 * std::abs(g11));
    CHECK(std::abs(H(1, 0) - g21) <= 1e-10 * std::abs(g21));
    // v1 = s d1, a2 = s^2 d2.
    CHECK(std::abs(H(2, 0) - s * g11) <= 1e-10 * std::abs(s * g11) + 1e-300);
    CHECK(std::abs(H(3, 0) - s * s * g21) <= 1e-10 * std::abs(s * s * g21) + 1e-300);
  }
  // Static compliance at 0 Hz: G11(0) = (k12 + k22) / (k11 k12 + k11 k22 + k12 k22).
  CHECK(result.H[0](0, 0).real() == Approx((0.12e6 + 0.24e6) / (1.38e6 * 0.12e6 + 1.38e6 * 0.24e6 + 0.12e6 * 0.24e6)));
  CHECK(result.H[0](0, 0).imag() == 0.0);
}

namespace {

void check_jacobian_against_finite_differences(const mbgen::Model& model, const std::vector<double>& freqs) {
  const Eigen::VectorXd p = model.info().default_values();
  const auto result = mbgen::frf_jacobian(model, p, freqs);
  const auto plain = mbgen::frf(model, p, freqs);
  REQUIRE(result.dH.size() == freqs.size());
  CHECK(result.lu_factorizations == freqs.size());
  for (std::size_t k = 0; k < freqs.size(); ++k) CHECK((result.H[k] - plain.H[k]).norm() == 0.0);
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    const double h = mbgen::test::central_step(p[i]);
    const auto fd = mbgen::test::central_difference(
        [&](const Eigen::VectorXd& q) { return mbgen::frf(model, q, freqs).H; }, p, i, h);
    // Compare entry by entry, relative to the size of that entry's derivative over the whole band (an entry
    // that is exactly zero analytically must also be zero to rounding in the differences).
    for (std::size_t k = 0; k < freqs.size(); ++k) {
      REQUIRE(result.dH[k].rows() == result.H[k].size());
      REQUIRE(result.dH[k].cols() == p.size());
      const Eigen::MatrixXcd analytic = result.derivative(k, i);
      INFO("parameter " << model.info().parameters[static_cast<std::size_t>(i)].name << ", f = " << freqs[k]);
      // Central differences cannot resolve less than the rounding of H over the step, ~eps |H| / h; allow ten
      // times that where the derivative itself is that small.
      const double rounding = 10 * std::numeric_limits<double>::epsilon() * result.H[k].norm() / h;
      CHECK((analytic - fd[k]).norm() <= 1e-6 * analytic.norm() + rounding);
    }
  }
}

}  // namespace

TEST_CASE("mdof2 FRF Jacobian matches central finite differences") {
  const mbgen::test::Mdof2Model model(/*extra_outputs=*/true);
  check_jacobian_against_finite_differences(model, {5.0, 60.0, 89.5, 110.0, 166.5, 300.0});
}

TEST_CASE("FRF Jacobian of a random model with parameter-dependent M, C, K, B, Cd, Cv, Ca") {
  const mbgen::test::RandomAffineModel model(5, 2, 3, 12, 42);
  check_jacobian_against_finite_differences(model, {0.0, 3.0, 7.5, 15.0, 40.0, 100.0});
}

TEST_CASE("FRF errors") {
  mbgen::ModelMatrices m;
  const double w = 2 * pi * 10;
  m.M = Eigen::MatrixXd::Constant(1, 1, 1.0);
  m.C = Eigen::MatrixXd::Zero(1, 1);
  m.K = Eigen::MatrixXd::Constant(1, 1, w * w);
  m.B = Eigen::MatrixXd::Ones(1, 1);
  m.Cd = Eigen::MatrixXd::Ones(1, 1);
  m.Cv = Eigen::MatrixXd::Zero(1, 1);
  m.Ca = Eigen::MatrixXd::Zero(1, 1);
  CHECK_NOTHROW(mbgen::frf(m, {9.0, 11.0}));
  CHECK_THROWS_WITH(mbgen::frf(m, {9.0, 10.0}), Catch::Contains("singular at 10 Hz"));

  mbgen::ModelDerivatives d;
  d.K.push_back({3, 0, 0, 1.0});
  CHECK_THROWS_WITH(mbgen::frf_jacobian(m, d, 2, {1.0}), Catch::Contains("derivative entry 0 of K"));
  d.K = {{0, 1, 0, 1.0}};
  CHECK_THROWS_AS(mbgen::frf_jacobian(m, d, 2, {1.0}), mbgen::DynamicsError);

  m.Cv = Eigen::MatrixXd::Zero(2, 1);
  CHECK_THROWS_WITH(mbgen::frf(m, {1.0}), Catch::Contains("matrix Cv is 2x1, expected 1x1"));

  const mbgen::test::Mdof2Model model;
  CHECK_THROWS_WITH(mbgen::frf(model, Eigen::VectorXd::Ones(3), {1.0}), Catch::Contains("has 8 parameters"));
}

namespace {

// H and every dH/dp at one frequency the dense way, independent of frf.cpp: P, dP, dB and dCout assembled entry by
// entry, then H = Cout X and dH = dCout X + Cout P^-1 (dB - dP X), X = P^-1 B, with Eigen's LU.
struct DenseReference {
  Eigen::MatrixXcd H;
  std::vector<Eigen::MatrixXcd> dH;
};

DenseReference dense_reference(const mbgen::ModelMatrices& m, const mbgen::ModelDerivatives& d, int params,
                               double f_hz) {
  const Eigen::Index n = m.M.rows();
  const cd s(0, 2 * pi * f_hz);
  const Eigen::MatrixXcd P = m.K.cast<cd>() + s * m.C.cast<cd>() + s * s * m.M.cast<cd>();
  const Eigen::MatrixXcd Cout = m.Cd.cast<cd>() + s * m.Cv.cast<cd>() + s * s * m.Ca.cast<cd>();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(P);
  const Eigen::MatrixXcd X = lu.solve(m.B.cast<cd>());
  DenseReference out{Cout * X, {}};
  for (int j = 0; j < params; ++j) {
    Eigen::MatrixXcd dP = Eigen::MatrixXcd::Zero(n, n), dB = Eigen::MatrixXcd::Zero(n, m.B.cols()),
                     dCout = Eigen::MatrixXcd::Zero(Cout.rows(), n);
    for (const auto& e : d.K) if (e.param == j) dP(e.row, e.col) += e.value;
    for (const auto& e : d.C) if (e.param == j) dP(e.row, e.col) += s * e.value;
    for (const auto& e : d.M) if (e.param == j) dP(e.row, e.col) += s * s * e.value;
    for (const auto& e : d.B) if (e.param == j) dB(e.row, e.col) += e.value;
    for (const auto& e : d.Cd) if (e.param == j) dCout(e.row, e.col) += e.value;
    for (const auto& e : d.Cv) if (e.param == j) dCout(e.row, e.col) += s * e.value;
    for (const auto& e : d.Ca) if (e.param == j) dCout(e.row, e.col) += s * s * e.value;
    out.dH.push_back(dCout * X + Cout * lu.solve(dB - dP * X));
  }
  return out;
}

}  // namespace

// A 120-coordinate banded model (a line of masses, springs and dampers to the first and second neighbours; the
// band LU path, band_lu.hpp) against a dense reference computed here with Eigen's LU: H = Cout P^-1 B and
// dH/dp = dCout X + Cout P^-1 (dB - dP X), X = P^-1 B.
TEST_CASE("FRF and Jacobian of a 120-coordinate banded model equal a dense reference") {
  const Eigen::Index n = 120;
  const int params = 3;  // every spring's stiffness scales with p0, damper with p1, mass with p2
  mbgen::ModelMatrices m;
  m.M = Eigen::MatrixXd::Zero(n, n);
  m.K = m.M;
  m.C = m.M;
  mbgen::ModelDerivatives d;
  auto spring = [&](Eigen::Index a, Eigen::Index b, double k, double c) {
    for (auto [r, s, sign] : {std::tuple{a, a, 1.0}, std::tuple{b, b, 1.0}, std::tuple{a, b, -1.0}, std::tuple{b, a, -1.0}}) {
      m.K(r, s) += sign * k;
      m.C(r, s) += sign * c;
      d.K.push_back({0, static_cast<int>(r), static_cast<int>(s), sign * k});
      d.C.push_back({1, static_cast<int>(r), static_cast<int>(s), sign * c});
    }
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    const double mass = 1.0 + 0.37 * static_cast<double>((i * 7) % 11);
    m.M(i, i) = mass;
    d.M.push_back({2, static_cast<int>(i), static_cast<int>(i), mass});
    m.K(i, i) += 1e4;  // to the ground
    if (i + 1 < n) spring(i, i + 1, 2e5 * (1.0 + 0.1 * static_cast<double>(i % 5)), 20.0);
    if (i + 2 < n) spring(i, i + 2, 5e4, 3.0);
  }
  m.B = Eigen::MatrixXd::Zero(n, 2);
  m.B(n - 1, 0) = 1;
  m.B(n / 2, 1) = 1;
  m.Cd = Eigen::MatrixXd::Zero(3, n);
  m.Cv = m.Cd;
  m.Ca = m.Cd;
  m.Cd(0, n - 1) = 1;
  m.Cv(1, 10) = 1;
  m.Ca(2, 70) = 1;
  const std::vector<double> freqs = {0.5, 3.0, 17.0, 41.0, 80.0, 150.0};
  const mbgen::FrfJacobianResult r = mbgen::frf_jacobian(m, d, params, freqs);
  // One column per solved right-hand side: the band path does the same solves as the dense one.
  CHECK(r.solved_columns == freqs.size() * 5);
  for (std::size_t k = 0; k < freqs.size(); ++k) {
    const DenseReference dense = dense_reference(m, d, params, freqs[k]);
    INFO("frequency " << freqs[k]);
    CHECK((r.H[k] - dense.H).norm() <= 1e-10 * dense.H.norm());
    for (int j = 0; j < params; ++j) CHECK((r.derivative(k, j) - dense.dH[j]).norm() <= 1e-9 * dense.dH[j].norm());
  }
}

// frf_jacobian sums the derivative entries of one parameter and row together (frf.cpp): entries listed in any order,
// parameters interleaved, the same (parameter, row, col) listed twice and one parameter in K, C and M at once must
// give what a dense dP, assembled here entry by entry, gives.
TEST_CASE("FRF Jacobian from derivative entries in any order and repeated equals a dense reference") {
  const Eigen::Index n = 6;
  const int params = 4;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  mbgen::ModelMatrices m;
  m.M = Eigen::MatrixXd::Identity(n, n) * 2.0;
  m.K = Eigen::MatrixXd::Zero(n, n);
  m.C = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    m.K(i, i) = 3e4 * (1.0 + 0.2 * static_cast<double>(i));
    m.C(i, i) = 5.0;
    if (i + 1 < n) m.K(i, i + 1) = m.K(i + 1, i) = -1e4, m.C(i, i + 1) = m.C(i + 1, i) = -1.0;
  }
  m.B = Eigen::MatrixXd::Zero(n, 2);
  m.B(0, 0) = 1, m.B(4, 1) = 1;
  m.Cd = Eigen::MatrixXd::Zero(3, n);
  m.Cv = m.Cd, m.Ca = m.Cd;
  m.Cd(0, 1) = 1, m.Cv(1, 3) = 1, m.Ca(2, 5) = 1;
  mbgen::ModelDerivatives d;
  std::uniform_int_distribution<int> index(0, static_cast<int>(n) - 1), parameter(0, params - 1);
  for (auto* entries : {&d.K, &d.C, &d.M})
    for (int e = 0; e < 25; ++e) entries->push_back({parameter(rng), index(rng), index(rng), unit(rng) * 1e3});
  d.K.push_back(d.K[3]);  // the same entry twice: both count
  d.C.push_back(d.C[0]);
  std::shuffle(d.K.begin(), d.K.end(), rng);
  d.B.push_back({2, 3, 1, 0.5});
  d.Cd.push_back({1, 0, 2, 0.25});
  const std::vector<double> freqs = {1.0, 12.0, 19.0, 60.0};
  const mbgen::FrfJacobianResult r = mbgen::frf_jacobian(m, d, params, freqs);
  for (std::size_t k = 0; k < freqs.size(); ++k) {
    const DenseReference dense = dense_reference(m, d, params, freqs[k]);
    for (int j = 0; j < params; ++j) {
      INFO("frequency " << freqs[k] << ", parameter " << j);
      CHECK((r.derivative(k, j) - dense.dH[j]).norm() <= 1e-10 * dense.dH[j].norm());
    }
  }
}

// The factors an FRF evaluation leaves (FrfFactorCache) serve a Jacobian at the same matrices: the same H and dH
// to the bit, no factorisation; at other matrices or frequencies the Jacobian factors afresh.
TEST_CASE("a Jacobian takes the factors of the FRF just evaluated at the same matrices, and only those") {
  const mbgen::test::RandomAffineModel model(5, 2, 3, 12, 42);
  const Eigen::VectorXd p = model.info().default_values();
  mbgen::ModelMatrices m;
  mbgen::ModelDerivatives d;
  model.evaluate(p, m);
  model.derivatives(p, d);
  const std::vector<double> freqs = {0.0, 3.0, 7.5, 15.0, 40.0, 100.0};
  const int count = static_cast<int>(p.size());
  std::vector<Eigen::MatrixXcd> H, dH;
  const auto keep = [&](std::size_t, const Eigen::MatrixXcd& h, const Eigen::MatrixXcd& dh) {
    H.push_back(h);
    dH.push_back(dh);
  };
  const mbgen::FrfJacobianResult reference = mbgen::frf_jacobian(m, d, count, freqs);
  mbgen::FrfFactorCache cache;
  std::vector<Eigen::MatrixXcd> plain;
  mbgen::frf(m, freqs, [&](std::size_t, const Eigen::MatrixXcd& h) { plain.push_back(h); }, &cache);
  const mbgen::FrfWork cached = mbgen::frf_jacobian(m, d, count, freqs, keep, &cache);
  CHECK(cached.lu_factorizations == 0);
  REQUIRE(H.size() == freqs.size());
  for (std::size_t k = 0; k < freqs.size(); ++k) {
    CHECK((H[k].array() == reference.H[k].array()).all());
    CHECK((plain[k].array() == reference.H[k].array()).all());
    CHECK((dH[k].array() == reference.dH[k].array()).all());
  }
  // Other matrices: factored afresh, and right.
  mbgen::ModelMatrices other = m;
  other.K(0, 0) *= 1.5;
  H.clear(), dH.clear();
  const mbgen::FrfWork fresh = mbgen::frf_jacobian(other, d, count, freqs, keep, &cache);
  CHECK(fresh.lu_factorizations == freqs.size());
  const mbgen::FrfJacobianResult other_reference = mbgen::frf_jacobian(other, d, count, freqs);
  for (std::size_t k = 0; k < freqs.size(); ++k) CHECK((dH[k].array() == other_reference.dH[k].array()).all());
  // Other frequencies: the same.
  std::vector<double> shifted = freqs;
  shifted.back() = 101.0;
  CHECK(mbgen::frf_jacobian(m, d, count, shifted, [](std::size_t, const auto&, const auto&) {}, &cache)
            .lu_factorizations == shifted.size());
  // A failed evaluation leaves nothing to take.
  mbgen::ModelMatrices singular = m;
  singular.M.setZero(), singular.C.setZero(), singular.K.setZero();
  CHECK_THROWS_AS(mbgen::frf(singular, freqs, [](std::size_t, const auto&) {}, &cache), mbgen::DynamicsError);
  CHECK(mbgen::frf_jacobian(m, d, count, freqs, [](std::size_t, const auto&, const auto&) {}, &cache)
            .lu_factorizations == freqs.size());
}
