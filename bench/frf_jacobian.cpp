// Benchmark: FRF plus its full parameter Jacobian (mbgen::frf_jacobian) at 1000 frequencies for a spindle-sized
// system (11 coordinates, 1 input, 3 outputs, 26 parameters: 13 springs and 13 dampers between coordinates or
// to ground, so every parameter derivative has at most four entries), against the cost of the 1000 complex LU
// factorisations + solves P^-1 B alone, measured in the same run. Also times one-sided finite differences
// (27 plain FRF evaluations) for comparison. Prints the ratios and the number of factorisations and solved
// right-hand-side columns that frf_jacobian reports.
//
// Usage: frf_jacobian [repetitions=5]
#include "mbgen/dynamics/frf.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>

namespace {

using cd = std::complex<double>;
constexpr int dofs = 11, inputs = 1, outputs = 3, springs = 13, frequencies = 1000;

struct System {
  mbgen::ModelMatrices m;
  mbgen::ModelDerivatives d;
};

// Masses/inertias on the diagonal; springs k_j and dampers c_j = 1e-5 k_j between coordinate pairs (a_j, b_j),
// b_j = -1 meaning ground. Parameters: k_0..k_12 (indices 0..12), c_0..c_12 (13..25). The first 10 springs
// form a chain to ground so that K is positive definite.
System make_system(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::uniform_int_distribution<int> coordinate(0, dofs - 1);
  System s;
  s.m.M = Eigen::MatrixXd::Zero(dofs, dofs);
  for (int i = 0; i < dofs; ++i) s.m.M(i, i) = i % 2 == 0 ? 5 + 20 * uniform(rng) : 0.05 + 0.3 * uniform(rng);
  s.m.K = Eigen::MatrixXd::Zero(dofs, dofs);
  s.m.C = Eigen::MatrixXd::Zero(dofs, dofs);
  for (int j = 0; j < springs; ++j) {
    int a = j < dofs ? j : coordinate(rng);
    int b = j == 0 ? -1 : (j < dofs ? j - 1 : coordinate(rng));
    if (a == b) b = -1;
    const double k = 3e7 + 1e8 * uniform(rng), c = 1e-5 * k;
    auto add = [&](Eigen::MatrixXd& X, std::vector<mbgen::DerivativeEntry>& dX, int param, double value) {
      X(a, a) += value;
      dX.push_back({param, a, a, 1.0});
      if (b >= 0) {
        X(b, b) += value;
        X(a, b) -= value;
        X(b, a) -= value;
        dX.push_back({param, b, b, 1.0});
        dX.push_back({param, a, b, -1.0});
        dX.push_back({param, b, a, -1.0});
      }
    };
    add(s.m.K, s.d.K, j, k);
    add(s.m.C, s.d.C, springs + j, c);
  }
  s.m.B = Eigen::MatrixXd::Zero(dofs, inputs);
  s.m.B(0, 0) = 1;
  s.m.Cd = Eigen::MatrixXd::Zero(outputs, dofs);
  s.m.Cd(0, 0) = 1;
  s.m.Cd(1, 0) = 0.5;
  s.m.Cd(1, 2) = 0.5;
  s.m.Cd(2, 4) = 1;
  s.m.Cv = Eigen::MatrixXd::Zero(outputs, dofs);
  s.m.Ca = Eigen::MatrixXd::Zero(outputs, dofs);
  return s;
}

template <class F>
double best_seconds(int repetitions, F&& f) {
  double best = 1e300;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const System s = make_system(2024);
  const int parameters = 2 * springs;
  std::vector<double> freqs(frequencies);
  for (int k = 0; k < frequencies; ++k) freqs[static_cast<std::size_t>(k)] = 10.0 + 1990.0 * k / (frequencies - 1);

  // Baseline: the complex LU factorisation and solve X = P^-1 B at every frequency, nothing else.
  double sink = 0;
  std::size_t baseline_solves = 0;
  const Eigen::MatrixXcd B = s.m.B.cast<cd>();
  const double t_lu = best_seconds(repetitions, [&] {
    baseline_solves = 0;
    for (double f : freqs) {
      const double w = 2 * 3.14159265358979323846 * f;
      Eigen::MatrixXcd P(dofs, dofs);
      P.real() = s.m.K - w * w * s.m.M;
      P.imag() = w * s.m.C;
      const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(P);
      const Eigen::MatrixXcd X = lu.solve(B);
      sink += std::abs(X(0, 0));
      ++baseline_solves;
    }
  });

  // The same with the adjoint solve P^-T Cout^T added: the linear algebra frf_jacobian cannot avoid.
  Eigen::MatrixXcd Cout = s.m.Cd.cast<cd>();
  const double t_lu_both = best_seconds(repetitions, [&] {
    for (double f : freqs) {
      const double w = 2 * 3.14159265358979323846 * f;
      Eigen::MatrixXcd P(dofs, dofs);
      P.real() = s.m.K - w * w * s.m.M;
      P.imag() = w * s.m.C;
      const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(P);
      const Eigen::MatrixXcd X = lu.solve(B);
      const Eigen::MatrixXcd Yt = lu.transpose().solve(Cout.transpose());
      sink += std::abs(X(0, 0)) + std::abs(Yt(0, 0));
    }
  });

  mbgen::FrfJacobianResult result;
  const double t_jac = best_seconds(repetitions, [&] {
    result = mbgen::frf_jacobian(s.m, s.d, parameters, freqs);
    sink += std::abs(result.dH.back()(0, 0));
  });

  const double t_frf = best_seconds(repetitions, [&] { sink += std::abs(mbgen::frf(s.m, freqs).H.back()(0, 0)); });

  // One-sided finite differences would need one more FRF per parameter (cost only; the values are not used).
  const double t_fd = (parameters + 1) * t_frf;

  std::size_t entries = s.d.K.size() + s.d.C.size();
  std::printf("system: %d coordinates, %d input(s), %d outputs, %d parameters (%zu derivative entries), %d frequencies\n",
              dofs, inputs, outputs, parameters, entries, frequencies);
  std::printf("best of %d repetitions\n", repetitions);
  std::printf("  complex LU + solve P^-1 B only : %9.3f ms (%zu factorisations, %zu solved columns)\n", 1e3 * t_lu,
              baseline_solves, baseline_solves * static_cast<std::size_t>(inputs));
  std::printf("  LU + direct and adjoint solves : %9.3f ms (%zu solved columns), ratio %.2f\n", 1e3 * t_lu_both,
              baseline_solves * static_cast<std::size_t>(inputs + outputs), t_lu_both / t_lu);
  std::printf("  frf (H only)                   : %9.3f ms\n", 1e3 * t_frf);
  std::printf("  frf_jacobian (H and all dH/dp) : %9.3f ms (%zu factorisations, %zu solved columns)\n", 1e3 * t_jac,
              result.lu_factorizations, result.solved_columns);
  std::printf("  ratio frf_jacobian / LU solves : %9.2f\n", t_jac / t_lu);
  std::printf("  finite differences (%d FRFs)   : %9.3f ms, ratio %.2f to LU solves\n", parameters + 1, 1e3 * t_fd,
              t_fd / t_lu);
  std::printf("(checksum %.6e)\n", sink);
  return 0;
}
