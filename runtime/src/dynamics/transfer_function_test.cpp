// Numeric transfer-function coefficients (mbgen/transfer_function.hpp) against exact rationals computed
// independently (sympy: det P and c adj(P) b of the hand-written 3-DOF system below, divided by det M).
#include "mbgen/transfer_function.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Cholesky>

#include <cmath>

namespace {

template <typename Scalar>
mbgen::TransferFunctionSystem<Scalar> three_dof() {
  using Mat = mbgen::DenseMatrix<Scalar>;
  auto q = [](int p, int r) { return Scalar(p) / Scalar(r); };
  mbgen::TransferFunctionSystem<Scalar> sys;
  sys.M = Mat(3, 3);
  sys.M << q(2, 1), q(1, 2), 0, q(1, 2), q(3, 1), q(1, 4), 0, q(1, 4), q(1, 1);
  sys.C = Mat(3, 3);
  sys.C << 3, -1, 0, -1, 2, -q(1, 2), 0, -q(1, 2), 1;
  sys.K = Mat(3, 3);
  sys.K << 50, -20, 0, -20, 45, -15, 0, -15, 30;
  sys.b = mbgen::DenseVector<Scalar>(3);
  sys.b << 1, 0, 0;
  sys.cd = mbgen::DenseRowVector<Scalar>(3);
  sys.cd << 0, 0, 1;
  sys.cv = mbgen::DenseRowVector<Scalar>(3);
  sys.cv << 0, q(1, 2), 0;
  sys.ca = mbgen::DenseRowVector<Scalar>(3);
  sys.ca << q(1, 10), 0, 0;
  return sys;
}

// Exact coefficients (ascending), from sympy.
const std::pair<long, long> exact_den[] = {{23600, 3}, {10040, 9}, {5260, 3}, {786, 5}, {3709, 45}, {107, 30}, {1, 1}};
const std::pair<long, long> exact_num[] = {{160, 3},   {520, 9},   {1004, 45}, {92, 45},
                                           {592, 225}, {11, 225}, {47, 900}};

template <typename Scalar>
Scalar max_relative_error(const std::vector<Scalar>& got, const std::pair<long, long> (&exact)[7]) {
  using std::abs;
  Scalar worst = 0;
  for (std::size_t k = 0; k < 7; ++k) {
    const Scalar x = Scalar(exact[k].first) / Scalar(exact[k].second);
    worst = std::max(worst, abs(got[k] - x) / abs(x));
  }
  return worst;
}

}  // namespace

TEST_CASE("3-DOF coefficients match exact rationals in double") {
  auto tf = mbgen::transfer_function_coefficients(three_dof<double>(), {0, 1, 2});
  REQUIRE(tf.numerator.size() == 7);
  REQUIRE(tf.denominator.size() == 7);
  CHECK(tf.denominator.back() == 1.0);
  CHECK(max_relative_error(tf.denominator, exact_den) < 1e-12);
  CHECK(max_relative_error(tf.numerator, exact_num) < 1e-12);
}

TEST_CASE("3-DOF coefficients are more accurate in long double") {
  auto tf = mbgen::transfer_function_coefficients(three_dof<long double>(), {0, 1, 2});
  CHECK(max_relative_error(tf.denominator, exact_den) < 1e-15L);
  CHECK(max_relative_error(tf.numerator, exact_num) < 1e-15L);
}

TEST_CASE("a block of a larger block-diagonal system gives the block's transfer function") {
  // Embed the 3-DOF system at coordinates {4, 0, 2} of a 5-DOF system whose other coordinates are uncoupled.
  auto small = three_dof<double>();
  const std::vector<int> where = {4, 0, 2};
  mbgen::TransferFunctionSystem<double> big;
  big.M = Eigen::MatrixXd::Identity(5, 5) * 7.0;
  big.C = Eigen::MatrixXd::Identity(5, 5) * 0.3;
  big.K = Eigen::MatrixXd::Identity(5, 5) * 90.0;
  big.b = Eigen::VectorXd::Zero(5);
  big.cd = big.cv = big.ca = Eigen::RowVectorXd::Zero(5);
  for (int i = 0; i < 3; ++i) {
    big.b[where[i]] = small.b[i];
    big.cd[where[i]] = small.cd[i];
    big.cv[where[i]] = small.cv[i];
    big.ca[where[i]] = small.ca[i];
    for (int j = 0; j < 3; ++j) {
      big.M(where[i], where[j]) = small.M(i, j);
      big.C(where[i], where[j]) = small.C(i, j);
      big.K(where[i], where[j]) = small.K(i, j);
    }
  }
  auto tf = mbgen::transfer_function_coefficients(big, where);
  CHECK(max_relative_error(tf.denominator, exact_den) < 1e-12);
  CHECK(max_relative_error(tf.numerator, exact_num) < 1e-12);
}

TEST_CASE("inconsistent sizes and bad blocks are rejected") {
  auto sys = three_dof<double>();
  CHECK_THROWS_AS(mbgen::transfer_function_coefficients(sys, {0, 3}), std::invalid_argument);
  CHECK_THROWS_AS(mbgen::transfer_function_coefficients(sys, {}), std::invalid_argument);
  sys.b = Eigen::VectorXd::Zero(2);
  CHECK_THROWS_AS(mbgen::transfer_function_coefficients(sys, {0, 1, 2}), std::invalid_argument);
}

TEST_CASE("coefficient Jacobians agree with central finite differences") {
  using Scalar = long double;
  const auto sys = three_dof<Scalar>();
  // Two "parameters": arbitrary (fixed, non-symmetric on purpose) derivative directions of every matrix.
  std::vector<mbgen::TransferFunctionSystem<Scalar>> dirs(2);
  for (int j = 0; j < 2; ++j) {
    auto& d = dirs[static_cast<std::size_t>(j)];
    d.M = d.C = d.K = mbgen::DenseMatrix<Scalar>::Zero(3, 3);
    d.b = mbgen::DenseVector<Scalar>::Zero(3);
    d.cd = d.cv = d.ca = mbgen::DenseRowVector<Scalar>::Zero(3);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        d.M(r, c) = Scalar(((r + 2 * c + j) % 3) - 1) / Scalar(5);
        d.C(r, c) = Scalar(((2 * r + c + j) % 4) - 1) / Scalar(3);
        d.K(r, c) = Scalar(((r * c + j) % 5) - 2) * Scalar(4);
      }
    d.b << Scalar(j), 1, Scalar(-1) / Scalar(2);
    d.cd << 1, 0, Scalar(j);
    d.cv << 0, Scalar(1) / Scalar(3), 0;
    d.ca << Scalar(1 - j) / Scalar(7), 0, 1;
  }
  const std::vector<int> block = {0, 1, 2};
  auto jac = mbgen::transfer_function_jacobian(sys, dirs, block);
  REQUIRE(jac.numerator.size() == 2);
  const Scalar h = 1e-6L;
  for (std::size_t j = 0; j < 2; ++j) {
    auto plus = sys, minus = sys;
    const auto& d = dirs[j];
    plus.M += h * d.M, plus.C += h * d.C, plus.K += h * d.K, plus.b += h * d.b;
    plus.cd += h * d.cd, plus.cv += h * d.cv, plus.ca += h * d.ca;
    minus.M -= h * d.M, minus.C -= h * d.C, minus.K -= h * d.K, minus.b -= h * d.b;
    minus.cd -= h * d.cd, minus.cv -= h * d.cv, minus.ca -= h * d.ca;
    auto tp = mbgen::transfer_function_coefficients(plus, block);
    auto tm = mbgen::transfer_function_coefficients(minus, block);
    for (std::size_t k = 0; k < 7; ++k) {
      const Scalar fd_num = (tp.numerator[k] - tm.numerator[k]) / (2 * h);
      const Scalar fd_den = (tp.denominator[k] - tm.denominator[k]) / (2 * h);
      INFO("parameter " << j << ", coefficient " << k);
      CHECK(static_cast<double>(std::abs(jac.numerator[j][k] - fd_num)) <=
            1e-7 * (1 + static_cast<double>(std::abs(fd_num))));
      CHECK(static_cast<double>(std::abs(jac.denominator[j][k] - fd_den)) <=
            1e-7 * (1 + static_cast<double>(std::abs(fd_den))));
    }
    CHECK(jac.denominator[j].back() == 0);
  }
}

// A line of n masses (springs to the neighbours and the ground, proportional damping) whose coefficients in s
// overflow double beyond about 50 masses: a_0 = det K / det M is the product of the squared natural frequencies
// (here ~(2 pi 300 Hz)^2 ~ 4e6 each).
template <typename Scalar>
mbgen::TransferFunctionSystem<Scalar> mass_line(int n) {
  using Mat = mbgen::DenseMatrix<Scalar>;
  mbgen::TransferFunctionSystem<Scalar> sys;
  sys.M = Mat::Zero(n, n);
  sys.K = Mat::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    sys.M(i, i) = Scalar(1) + Scalar(i % 3) / Scalar(4);
    sys.K(i, i) += Scalar(2e6);
    if (i + 1 < n) {
      sys.K(i, i) += Scalar(3e6);
      sys.K(i + 1, i + 1) += Scalar(3e6);
      sys.K(i, i + 1) -= Scalar(3e6);
      sys.K(i + 1, i) -= Scalar(3e6);
    }
  }
  sys.C = Scalar(1e-5) * sys.K + Scalar(2) * sys.M;
  sys.b = mbgen::DenseVector<Scalar>::Zero(n);
  sys.b(n - 1) = 1;
  sys.cd = mbgen::DenseRowVector<Scalar>::Zero(n);
  sys.cd(0) = 1;
  sys.cv = mbgen::DenseRowVector<Scalar>::Zero(n);
  sys.ca = mbgen::DenseRowVector<Scalar>::Zero(n);
  return sys;
}

TEST_CASE("coefficients beyond double's range: scaled form in double, a clear error, long double unscaled") {
  const int n = 60;
  std::vector<int> block(n);
  for (int i = 0; i < n; ++i) block[static_cast<std::size_t>(i)] = i;
  const auto sd = mbgen::transfer_function_scaled(mass_line<double>(n), block);
  const auto sl = mbgen::transfer_function_scaled(mass_line<long double>(n), block);
  REQUIRE(sd.denominator.size() == 121);
  CHECK(sd.denominator.back() == 1.0);
  // The scaled coefficients are finite and moderate in double and agree with long double's: relative to the
  // largest, as the routine's accuracy is stated.
  double scale = 0, worst = 0;
  for (std::size_t k = 0; k < sd.denominator.size(); ++k) {
    REQUIRE(std::isfinite(sd.denominator[k]));
    scale = std::max(scale, static_cast<double>(std::fabs(sl.denominator[k])));
  }
  for (std::size_t k = 0; k < sd.denominator.size(); ++k)
    worst = std::max(worst, std::fabs(sd.denominator[k] - static_cast<double>(sl.denominator[k])) / scale);
  CHECK(worst < 1e-10);
  CHECK(scale < 1e60);  // a_0 itself is ~1e390
  CHECK(std::fabs(static_cast<double>(sl.rho / sd.rho) - 1) < 1e-12);

  // In s: long double holds them (each the scaled one times rho^(n - k), n = 120); double cannot and says so
  // instead of returning infinities. (a_0 itself is accurate only relative to the largest scaled coefficient,
  // ~1e-20 here for 60 masses: the stated measure of the routine, not checked digit by digit.)
  const auto tl = mbgen::transfer_function_coefficients(mass_line<long double>(n), block);
  CHECK(std::log10(tl.denominator[0]) > 300);
  for (std::size_t k = 0; k < tl.denominator.size(); ++k) {
    const long double expected = sl.denominator[k] * std::pow(sl.rho, static_cast<long double>(120 - k));
    CHECK(std::fabs(static_cast<double>((tl.denominator[k] - expected) / expected)) < 1e-15);
  }
  // The exact a_0 = det K / det M, by the product of Cholesky pivots, to the accuracy stated in the scaled measure.
  const auto K = mass_line<long double>(n).K, M = mass_line<long double>(n).M;
  long double log_det_k = 0, log_det_m = 0;
  const Eigen::LLT<mbgen::DenseMatrix<long double>> llt(K);
  for (int i = 0; i < n; ++i) log_det_k += 2 * std::log(llt.matrixL()(i, i)), log_det_m += std::log(M(i, i));
  const long double a0 = std::exp(log_det_k - log_det_m);
  CHECK(std::fabs(static_cast<double>((tl.denominator[0] - a0) / (scale * std::pow(sl.rho, 120.0L)))) < 1e-15);
  CHECK_THROWS_AS(mbgen::transfer_function_coefficients(mass_line<double>(n), block), std::overflow_error);
  // A small line still fits double: no error there.
  CHECK_NOTHROW(mbgen::transfer_function_coefficients(mass_line<double>(10), std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
}
