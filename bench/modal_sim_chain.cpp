// Benchmark: modal analysis and simulation at machine scale (issue 14): the chain of N six-coordinate bodies
// (compiler/symbolic/test_chain_model.hpp) through the in-process evaluator, for N = 4, 8, 16, 32:
//
//   modal_sim_chain [N...]
//
// Prints per N the time of mbgen::modal_analysis (complex modes of the 2n-state system) against Eigen's
// EigenSolver of the 2n x 2n state matrix alone (the dense eigen yardstick), and of mbgen::simulate (1000 samples
// at 10 kHz, zero-order hold: discretisation plus the state recursion) against one dense 2n x 2n matrix-vector
// product per sample, the recursion's own cost.
#include <Eigen/Eigenvalues>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"
#include "mbgen/dynamics/model_modes.hpp"
#include "mbgen/dynamics/simulate.hpp"
#include "mbgen/dynamics/state_space.hpp"
#include "seconds_since.hpp"
#include "symbolic/test_chain_model.hpp"

using mbgen::bench::seconds_since;

int main(int argc, char** argv) {
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if (sizes.empty()) sizes = {4, 8, 16, 32};
  std::printf("%4s %5s | %10s %12s %6s | %12s %14s %6s\n", "N", "DOF", "modal [s]", "eig(A) [s]", "ratio",
              "simulate [s]", "2n x 2n x 1000", "ratio");
  for (int n : sizes) {
    const mbgen::ir::ModelIr ir = mbgen::frontend::parse_string(mbgen::symbolic::test::chain_model_text(n), "chain.mdl");
    const auto model = mbgen::evaluator::make_evaluator(ir, {{}, false});
    mbgen::ModelMatrices m;
    model->evaluate(model->info().default_values(), m);
    auto t0 = std::chrono::steady_clock::now();
    const auto modes = mbgen::modal_analysis(m.M, m.C, m.K);
    const double t_modal = seconds_since(t0);
    const mbgen::StateSpace ss = mbgen::state_space(m);
    t0 = std::chrono::steady_clock::now();
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(ss.A, true);
    const double t_eig = seconds_since(t0);

    const int samples = 1000;
    Eigen::MatrixXd u = Eigen::MatrixXd::Zero(samples, 1);
    u(0, 0) = 1;
    t0 = std::chrono::steady_clock::now();
    const Eigen::MatrixXd y = mbgen::simulate(m, u, 1e-4, mbgen::InputHold::ZeroOrder);
    const double t_sim = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    Eigen::VectorXd x = Eigen::VectorXd::Ones(ss.A.rows());
    for (int k = 0; k < samples; ++k) x = (ss.A * x).eval() / ss.A.norm();  // one dense product per sample
    const double t_mv = seconds_since(t0);
    std::printf("%4d %5d | %10.4f %12.4f %6.2f | %12.4f %14.4f %6.1f   (%zu modes, %ld eigenvalues, |y| %.3g, %.2g)\n",
                n, 6 * n, t_modal, t_eig, t_modal / t_eig, t_sim, t_mv, t_sim / t_mv, modes.size(),
                static_cast<long>(eig.eigenvalues().size()), y.norm(), x.norm());
    std::fflush(stdout);
  }
  return 0;
}
