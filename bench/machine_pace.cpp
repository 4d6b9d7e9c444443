// machine_pace: a fixed workload that measures the machine, not mbgen. Wall times of a diagnosis vary with the
// machine's pace (by up to two times between the machines these benchmarks ran on, and by 10-30 % within a
// session on one); diagnose_wall_times.sh runs this before and after its cases and scales their seconds to a
// reference pace, so that a change of the code and a change of the machine can be told apart.
//
// The work is the diagnosis's inner loop written with Eigen alone, so that no change to mbgen moves it: on each of
// two threads (a diagnosis keeps both cores busy), an FRF and its adjoint of a fixed 12-coordinate model on 1500
// lines (a dense complex LU per line, one solve and a transposed solve of three right-hand sides) and a Householder
// QR of a fixed 9000 x 31 real matrix, 80 times a round. Prints the median of five rounds in seconds.
//   BUILD/bench/machine_pace
#include <Eigen/Dense>

#include <algorithm>
#include <complex>
#include <cstdio>
#include <random>
#include <thread>
#include <vector>

#include "seconds_since.hpp"

namespace {

using cd = std::complex<double>;

struct Work {
  Eigen::MatrixXd M, C, K, J;
  Eigen::MatrixXcd B, Cout;
};

Work make_work() {
  constexpr int n = 12, outputs = 3, rows = 9000, columns = 31;
  std::mt19937_64 engine(20261130);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto random = [&](int r, int c) {
    Eigen::MatrixXd a(r, c);
    for (int j = 0; j < c; ++j)
      for (int i = 0; i < r; ++i) a(i, j) = u(engine);
    return a;
  };
  Work w;
  const Eigen::MatrixXd a = random(n, n), b = random(n, n), c = random(n, n);
  // Symmetric positive definite mass and stiffness, light damping: resonances inside the band, as in a model.
  w.M = a * a.transpose() + n * Eigen::MatrixXd::Identity(n, n);
  w.K = 4e6 * (b * b.transpose() + n * Eigen::MatrixXd::Identity(n, n));
  w.C = 20 * (c * c.transpose() + n * Eigen::MatrixXd::Identity(n, n));
  w.B = Eigen::MatrixXcd::Zero(n, 1);
  w.B(0, 0) = 1;
  w.Cout = random(outputs, n).cast<cd>();
  w.J = random(rows, columns);
  return w;
}

// One round's work on one thread; returns a checksum so that nothing is optimised away.
double one_round(const Work& w) {
  double sum = 0;
  for (int repeat = 0; repeat < 80; ++repeat) {
    for (int line = 0; line < 1500; ++line) {
      const double omega = 2 * 3.141592653589793 * (5 + line);
      const Eigen::MatrixXcd P =
          (w.K - omega * omega * w.M).cast<cd>() + cd(0, omega) * w.C.cast<cd>();
      const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(P);
      const Eigen::MatrixXcd X = lu.solve(w.B);
      const Eigen::MatrixXcd Y = lu.transpose().solve(w.Cout.transpose());
      sum += std::abs((w.Cout * X)(0, 0)) + std::abs(Y(0, 0));
    }
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(w.J);
    sum += std::abs(qr.matrixQR()(0, 0));
  }
  return sum;
}

}  // namespace

int main() {
  const Work work = make_work();
  std::vector<double> seconds;
  double checksum = 0;
  for (int round = 0; round < 5; ++round) {
    const auto t0 = std::chrono::steady_clock::now();
    double a = 0, b = 0;
    std::thread other([&] { b = one_round(work); });
    a = one_round(work);
    other.join();
    seconds.push_back(mbgen::bench::seconds_since(t0));
    checksum += a + b;
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("machine pace: %.3f s (median of 5 rounds; checksum %.6g)\n", seconds[2], checksum);
  return 0;
}
