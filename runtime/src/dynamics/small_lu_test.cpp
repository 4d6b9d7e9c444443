// The small in-place LU against Eigen's PartialPivLU (an independent implementation): solves with A and A^T,
// pivoting (a zero leading entry), and the singularity ratio.
#include "small_lu.hpp"

#include <Eigen/LU>

#include <catch2/catch.hpp>

#include "mbgen_test/random_matrix.hpp"

#include <random>

using mbgen::detail::SmallLu;
using cd = std::complex<double>;
using mbgen::test::random_complex_matrix;

TEST_CASE("small LU solves A x = b and A^T y = c like Eigen's partial-pivoting LU", "[dynamics][lu]") {
  std::mt19937 rng(11);
  for (Eigen::Index n : {1, 2, 5, 11}) {
    const Eigen::MatrixXcd A = random_complex_matrix(n, n, rng), b = random_complex_matrix(n, 3, rng);
    SmallLu lu;
    lu.resize(n);
    lu.matrix() = A;
    CHECK(lu.factor() > 0);
    Eigen::MatrixXcd x = b, y = b;
    lu.solve(x);
    lu.solve_transposed(y);
    const Eigen::PartialPivLU<Eigen::MatrixXcd> ref(A), ref_t(Eigen::MatrixXcd(A.transpose()));
    INFO("n = " << n);
    CHECK((x - ref.solve(b)).norm() <= 1e-12 * ref.solve(b).norm());
    CHECK((y - ref_t.solve(b)).norm() <= 1e-12 * ref_t.solve(b).norm());
    CHECK((A * x - b).norm() <= 1e-12 * A.norm() * x.norm());
  }
}

TEST_CASE("small LU pivots past a zero leading entry and reports singular matrices", "[dynamics][lu]") {
  SmallLu lu;
  lu.resize(2);
  lu.matrix() << 0.0, cd(2, 1), 3.0, 1.0;  // needs a row swap
  CHECK(lu.factor() > 0.1);
  Eigen::MatrixXcd x(2, 1);
  x << 1.0, 2.0;
  lu.solve(x);
  // [0, 2+j; 3, 1] x = [1; 2]: x1 = 1 / (2 + j), x0 = (2 - x1) / 3.
  const cd x1 = 1.0 / cd(2, 1);
  CHECK(std::abs(x(1, 0) - x1) < 1e-15);
  CHECK(std::abs(x(0, 0) - (2.0 - x1) / 3.0) < 1e-15);

  lu.matrix() << 1.0, 2.0, 2.0, 4.0;
  CHECK(lu.factor() < 1e-15);
  lu.resize(0);
  CHECK(lu.factor() == 1);
}
