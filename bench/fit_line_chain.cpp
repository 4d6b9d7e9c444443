// Benchmark: FRF fits of an identifiable chain at machine scale (issue 14, "fits of a 100-parameter model from FRFs
// in seconds"): the chain of compiler/evaluator/test_line_chain.hpp (N bodies along one axis, 3N parameters, a
// force on the tip, accelerometers on every third body and the first), N = 8 .. 66 (24 .. 198 parameters).
//
//   fit_line_chain [--starts S] [--spread F] [--draws D] [N...]      (default: S = 1, F = 0.2, D = 2, N = 8 16 33 50 66)
//
// Per N and draw (seed = draw): the truth is every parameter's nominal value times a factor uniform in [1 - F, 1 + F];
// the FRFs come from the hand-assembled tridiagonal chain (test_line_chain.hpp, independent of the compiler and the
// runtime) at 400 log-spaced lines over 2..400 Hz, with 1 % complex noise proportional to |H| and the matching
// coherence. The fit starts at the model's defaults: S starts (the defaults, then S - 1 within a factor 1.3),
// log-ratio search to a relative decrease of 1e-4, then the weighted refinement; two threads. Printed: CPU and
// wall time of `mbgen::fit` (the model's derivation is outside), accepted iterations, the parameters kept
// identifiable, the singular-value ratio of the unit-column Jacobian at the estimate, the largest relative error
// of the masses and stiffnesses and of the dampers, the largest |estimate - truth| / std, and whether the fit
// reached the truth (every |z| < 5). Then the growth exponent of the CPU time over the runs that reached it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "evaluator/symbolic_evaluator.hpp"
#include "evaluator/test_line_chain.hpp"
#include "frontend/parser.hpp"
#include "mbgen/estimation/fit.hpp"

namespace {

using namespace mbgen;
namespace lc = mbgen::test::line_chain;

constexpr int kEvery = 3;

double cpu_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  int starts = 1, draws = 2;
  double spread = 0.2;
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--starts" && i + 1 < argc) starts = std::atoi(argv[++i]);
    else if (a == "--spread" && i + 1 < argc) spread = std::atof(argv[++i]);
    else if (a == "--draws" && i + 1 < argc) draws = std::atoi(argv[++i]);
    else sizes.push_back(std::atoi(a.c_str()));
  }
  if (sizes.empty()) sizes = {8, 16, 33, 50, 66};
  std::printf("truth within +-%.0f %% of the priors, %d start(s), 400 lines, 1 %% noise\n", 100 * spread, starts);
  std::printf("%4s %6s %4s %6s %5s | %8s %8s %5s %5s %9s | %8s %8s %7s %s\n", "N", "params", "chan", "rows", "draw",
              "CPU [s]", "wall [s]", "iter", "ident", "sv ratio", "m,k err", "c err", "max|z|", "truth?");
  std::vector<double> log_p, log_t;
  for (int n : sizes) {
    const ir::ModelIr ir = frontend::parse_string(lc::model_text(n, kEvery), "line_chain.mdl");
    const auto model = evaluator::make_evaluator(ir);
    const ModelInfo& info = model->info();
    for (int draw = 1; draw <= draws; ++draw) {
      const lc::Draw d = lc::draw(info, n, kEvery, static_cast<unsigned>(draw), spread);
      const Eigen::VectorXd& truth = d.truth;
      const FrfData& data = d.data;
      FitOptions options;
      options.starts = starts;
      options.spread = 1.3;
      options.threads = 2;
      options.search_cost_tolerance = 1e-4;
      options.frf_weighting.floor = 1e-9;
      const double c0 = cpu_now();
      const auto t0 = std::chrono::steady_clock::now();
      const FitResult r = fit(*model, {DataSet(data)}, options);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double cpu = cpu_now() - c0;
      double err_mk = 0, err_c = 0, max_z = 0;
      bool all_std = true;
      for (const ParameterEstimate& p : r.parameters) {
        const double t = truth[info.parameter_index(p.name)];
        double& err = p.name[0] == 'c' ? err_c : err_mk;
        err = std::max(err, std::fabs(p.value / t - 1));
        if (p.std > 0) max_z = std::max(max_z, std::fabs(p.value - t) / p.std);
        else all_std = false;
      }
      const bool reached = all_std && max_z < 5;
      const double ratio = r.singular_values.size() ? r.singular_values.tail(1)[0] / r.singular_values[0] : 0;
      std::printf("%4d %6zu %4zu %6ld %5d | %8.2f %8.2f %5zu %5zu %9.1e | %8.4f %8.4f %7.2f %s\n", n,
                  info.parameters.size(), data.channels.size(), r.residual_count, draw, cpu, wall,
                  r.cost_history.size() - 1, r.estimated.size(), ratio, err_mk, err_c, max_z, reached ? "yes" : "no");
      std::fflush(stdout);
      if (reached) {
        log_p.push_back(std::log(double(info.parameters.size())));
        log_t.push_back(std::log(cpu));
      }
    }
  }
  if (log_p.size() >= 2) {
    const double np = double(log_p.size());
    double mp = 0, mt = 0;
    for (std::size_t i = 0; i < log_p.size(); ++i) mp += log_p[i] / np, mt += log_t[i] / np;
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < log_p.size(); ++i) sxy += (log_p[i] - mp) * (log_t[i] - mt), sxx += (log_p[i] - mp) * (log_p[i] - mp);
    if (sxx > 0) std::printf("growth of the CPU time over the fits that reached the truth: t ~ params^%.2f\n", sxy / sxx);
  }
  return 0;
}
