// Benchmark: FRF with its full parameter Jacobian at machine scale (issue 14): the chain of N six-coordinate
// bodies (compiler/symbolic/test_chain_model.hpp; 6N coordinates, 3N parameters, 1 input, 2 outputs) through the
// in-process evaluator, at 200 frequencies, for N = 4, 8, 16, 32, 64:
//
//   frf_chain [N...]
//
// Prints per N the time of mbgen::frf_jacobian (band LU when it pays, runtime/src/dynamics/band_lu.hpp) and, as
// the dense yardstick, Eigen's PartialPivLU of P(jw) with the solves X = P^-1 B and Y^T = P^-T Cout^T alone, and
// the largest relative difference of the two FRFs.
#include <Eigen/LU>

#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"
#include "mbgen/dynamics/frf.hpp"
#include "seconds_since.hpp"
#include "symbolic/test_chain_model.hpp"

using mbgen::bench::seconds_since;

int main(int argc, char** argv) {
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if (sizes.empty()) sizes = {4, 8, 16, 32, 64};
  std::vector<double> freqs;
  for (int k = 0; k < 200; ++k) freqs.push_back(5.0 + 2.0 * k);
  std::printf("chain of N bodies, FRF + Jacobian at %zu frequencies\n\n", freqs.size());
  std::printf("%4s %5s %6s | %12s %14s %7s | %10s\n", "N", "DOF", "params", "frf_jac [s]", "dense LU [s]", "ratio",
              "H vs dense");
  for (int n : sizes) {
    const mbgen::ir::ModelIr ir = mbgen::frontend::parse_string(mbgen::symbolic::test::chain_model_text(n), "chain.mdl");
    const auto model = mbgen::evaluator::make_evaluator(ir, {{}, false});
    const Eigen::VectorXd p = model->info().default_values();
    mbgen::ModelMatrices m;
    mbgen::ModelDerivatives d;
    model->evaluate(p, m);
    model->derivatives(p, d);
    auto t0 = std::chrono::steady_clock::now();
    const mbgen::FrfJacobianResult r = mbgen::frf_jacobian(m, d, static_cast<int>(p.size()), freqs);
    const double t_jac = seconds_since(t0);

    t0 = std::chrono::steady_clock::now();
    using cd = std::complex<double>;
    double worst = 0, checksum = 0;  // checksum: keeps the adjoint solve from being optimised away
    for (std::size_t k = 0; k < freqs.size(); ++k) {
      const cd s(0, 2 * M_PI * freqs[k]);
      const Eigen::MatrixXcd P = m.K.cast<cd>() + s * m.C.cast<cd>() + s * s * m.M.cast<cd>();
      const Eigen::MatrixXcd Cout = m.Cd.cast<cd>() + s * m.Cv.cast<cd>() + s * s * m.Ca.cast<cd>();
      const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(P);
      const Eigen::MatrixXcd X = lu.solve(m.B.cast<cd>());
      const Eigen::MatrixXcd Yt = lu.transpose().solve(Cout.transpose());
      const Eigen::MatrixXcd H = Cout * X;
      worst = std::max(worst, (H - r.H[k]).norm() / H.norm());
      checksum += std::abs(Yt(0, 0));
    }
    const double t_dense = seconds_since(t0);
    std::printf("%4d %5d %6d | %12.4f %14.4f %7.2f | %10.1e\n", n, 6 * n, static_cast<int>(p.size()), t_jac, t_dense,
                t_jac / t_dense, worst);
    if (!std::isfinite(checksum)) std::printf("  (adjoint solve not finite)\n");
    std::fflush(stdout);
  }
  return 0;
}
