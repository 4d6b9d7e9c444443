// Benchmark: an FRF output-error fit at machine scale (issue 14): the chain of N six-coordinate bodies
// (compiler/symbolic/test_chain_model.hpp: 3N parameters, one force input, two displacement outputs) through the
// in-process evaluator. The truth is the model's defaults times factors drawn from a seed (within +-2 %: lightly damped peaks, a local fit needs a start within about a half-power bandwidth), its
// FRFs at 400 frequencies (log-spaced, 5..2000 Hz) get 1 % complex noise; the fit starts at the defaults:
//
//   fit_chain [N...]        (default N = 16 24 32)
//
// One local Levenberg-Marquardt fit (starts = 1, no log-ratio search: the problem the FRF Jacobian's cost sets)
// and one start with the log-ratio search, wall and CPU time, iterations, and the largest relative error of the
// parameters the fit reports identifiable. The data come from the code under test (mbgen::frf): a speed benchmark,
// not an accuracy test.
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <vector>

#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"
#include "mbgen/data/data_set.hpp"
#include "mbgen/estimation/fit.hpp"
#include "mbgen/dynamics/frf.hpp"
#include "symbolic/test_chain_model.hpp"

namespace {

using namespace mbgen;

double cpu_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if (sizes.empty()) sizes = {16, 24, 32};
  std::vector<double> freqs;
  for (int k = 0; k < 400; ++k) freqs.push_back(5.0 * std::pow(400.0, k / 399.0));
  std::printf("%4s %5s %6s | %-18s %9s %9s %6s %12s %9s %12s\n", "N", "DOF", "params", "fit", "wall [s]", "CPU [s]",
              "iter", "CPU/iter [s]", "estimated", "max rel err");
  for (int n : sizes) {
    const ir::ModelIr ir = frontend::parse_string(symbolic::test::chain_model_text(n), "chain.mdl");
    const auto model = evaluator::make_evaluator(ir, {{}, false});
    const ModelInfo& info = model->info();
    std::mt19937 rng(static_cast<unsigned>(1000 + n));
    std::uniform_real_distribution<double> factor(0.98, 1.02);
    std::normal_distribution<double> noise(0.0, 0.01 / std::sqrt(2.0));
    Eigen::VectorXd truth = info.default_values();
    for (Eigen::Index i = 0; i < truth.size(); ++i) truth[i] *= factor(rng);
    const FrfResult h = frf(*model, truth, freqs);
    FrfData data;
    data.file = "chain" + std::to_string(n) + " (synthetic)";
    data.f_hz = Eigen::Map<const Eigen::VectorXd>(freqs.data(), static_cast<Eigen::Index>(freqs.size()));
    for (std::size_t o = 0; o < info.outputs.size(); ++o) {
      FrfChannel c;
      c.output = info.outputs[o];
      c.input = info.inputs[0];
      c.values.resize(static_cast<Eigen::Index>(freqs.size()));
      for (std::size_t k = 0; k < freqs.size(); ++k) {
        const std::complex<double> v = h.H[k](static_cast<Eigen::Index>(o), 0);
        c.values[static_cast<Eigen::Index>(k)] = v * std::complex<double>(1 + noise(rng), noise(rng));
      }
      data.channels.push_back(std::move(c));
    }
    for (int search = 0; search < 2; ++search) {
      FitOptions options;
      options.starts = 1;
      options.log_search = search == 1;
      if (std::getenv("FIT_CHAIN_PROGRESS"))
        options.progress = [](const FitProgress& p) {
          if (p.iteration % 10 == 0) std::fprintf(stderr, "  %s %d: cost %.6g\n", p.stage.c_str(), p.iteration, p.cost);
        };
      const double c0 = cpu_now();
      const auto t0 = std::chrono::steady_clock::now();
      const FitResult r = fit(*model, {DataSet(data)}, options);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double cpu = cpu_now() - c0;
      double worst = 0;
      for (const std::string& name : r.estimated) {
        const int i = info.parameter_index(name);
        worst = std::max(worst, std::fabs(r.values[i] / truth[i] - 1));
      }
      std::printf("%4d %5d %6zu | %-18s %9.2f %9.2f %6d %12.3f %9zu %12.2e\n", n, 6 * n, info.parameters.size(),
                  search ? "1 start, search" : "local LM", wall, cpu, r.iterations,
                  cpu / std::max(1, r.iterations), r.estimated.size(), worst);
      std::fflush(stdout);
    }
  }
  return 0;
}
