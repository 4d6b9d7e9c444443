// The band LU against Eigen's dense partial-pivoting LU (an independent implementation): solves with A and A^T on
// random band matrices, small and of ~100 rows, with pivoting forced (small diagonals), unequal bands, the
// singularity ratio, and the bandwidth and cost rule.
#include "band_lu.hpp"

#include <Eigen/LU>

#include <catch2/catch.hpp>

#include "mbgen_test/random_matrix.hpp"

#include <random>

using mbgen::detail::BandLu;
using mbgen::detail::Bandwidth;
using cd = std::complex<double>;
using mbgen::test::random_complex_matrix;

namespace {

// Random n x n with kl sub- and ku superdiagonals; a small diagonal so that partial pivoting must interchange.
Eigen::MatrixXcd random_band(Eigen::Index n, Bandwidth b, double diagonal, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXcd a = Eigen::MatrixXcd::Zero(n, n);
  for (Eigen::Index c = 0; c < n; ++c)
    for (Eigen::Index r = std::max<Eigen::Index>(0, c - b.upper); r <= std::min(n - 1, c + b.lower); ++r)
      a(r, c) = r == c ? cd(diagonal * normal(rng), diagonal * normal(rng)) : cd(normal(rng), normal(rng));
  return a;
}

}  // namespace

TEST_CASE("band LU solves A x = b and A^T y = c like a dense LU", "[dynamics][lu]") {
  std::mt19937 rng(5);
  // A dominant diagonal (well conditioned, no interchanges needed) for every band shape, and a small one
  // (interchanges forced) for bands with room to pivot in both directions.
  struct Case {
    Bandwidth band;
    double diagonal;
  };
  const Case cases[] = {{{0, 0}, 1}, {{1, 1}, 10}, {{2, 0}, 10}, {{0, 3}, 10}, {{3, 1}, 10}, {{11, 11}, 40},
                        {{3, 1}, 1e-3}, {{2, 3}, 1e-3}, {{11, 11}, 1e-3}};
  for (Eigen::Index n : {1, 2, 7, 30, 120}) {
    for (const Case& k : cases) {
      const Bandwidth b{std::min(k.band.lower, n - 1), std::min(k.band.upper, n - 1)};
      const Eigen::MatrixXcd A = random_band(n, b, k.diagonal, rng), rhs = random_complex_matrix(n, 3, rng);
      BandLu lu;
      lu.resize(n, b);
      lu.set_zero();
      for (Eigen::Index c = 0; c < n; ++c)
        for (Eigen::Index r = std::max<Eigen::Index>(0, c - b.upper); r <= std::min(n - 1, c + b.lower); ++r)
          lu.at(r, c) = A(r, c);
      CHECK(lu.factor() > 0);
      Eigen::MatrixXcd x = rhs, y = rhs;
      lu.solve(x);
      lu.solve_transposed(y);
      const Eigen::PartialPivLU<Eigen::MatrixXcd> ref(A), ref_t(Eigen::MatrixXcd(A.transpose()));
      INFO("n = " << n << ", band " << b.lower << "/" << b.upper << ", diagonal " << k.diagonal);
      // Backward stable like the dense LU: residuals relative to |A| |x|; forward errors within the condition.
      CHECK((A * x - rhs).norm() <= 1e-12 * A.norm() * x.norm());
      CHECK((A.transpose() * y - rhs).norm() <= 1e-12 * A.norm() * y.norm());
      const double tolerance = 1e-13 / ref.rcond();
      CHECK((x - ref.solve(rhs)).norm() <= tolerance * x.norm());
      CHECK((y - ref_t.solve(rhs)).norm() <= tolerance * y.norm());
    }
  }
}

TEST_CASE("band LU reports a singular matrix and factors again in its buffers", "[dynamics][lu]") {
  const Eigen::Index n = 40;
  const Bandwidth b{2, 1};
  std::mt19937 rng(9);
  Eigen::MatrixXcd A = random_band(n, b, 1.0, rng);
  A.col(17).setZero();  // an exactly singular column
  BandLu lu;
  lu.resize(n, b);
  auto load = [&](const Eigen::MatrixXcd& m) {
    lu.set_zero();
    for (Eigen::Index c = 0; c < n; ++c)
      for (Eigen::Index r = std::max<Eigen::Index>(0, c - b.upper); r <= std::min(n - 1, c + b.lower); ++r)
        lu.at(r, c) = m(r, c);
  };
  load(A);
  CHECK(lu.factor() == 0);
  const Eigen::MatrixXcd good = random_band(n, b, 1.0, rng), rhs = random_complex_matrix(n, 1, rng);
  load(good);
  CHECK(lu.factor() > 0);
  Eigen::MatrixXcd x = rhs;
  lu.solve(x);
  CHECK((good * x - rhs).norm() <= 1e-12 * good.norm() * x.norm());
}

TEST_CASE("bandwidth of a pattern, and when band storage pays", "[dynamics][lu]") {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(50, 50), b = a;
  a(10, 7) = 1;   // 3 below the diagonal
  b(4, 9) = -2;   // 5 above
  const Bandwidth w = mbgen::detail::bandwidth_of({&a, &b});
  CHECK(w.lower == 3);
  CHECK(w.upper == 5);
  CHECK(mbgen::detail::band_pays(96, {11, 11}));      // a chain of 16 six-coordinate bodies
  CHECK(!mbgen::detail::band_pays(20, {1, 1}));       // small models keep the dense LU
  CHECK(!mbgen::detail::band_pays(40, {39, 39}));     // full
}
