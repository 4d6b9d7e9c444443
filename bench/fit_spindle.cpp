// Benchmark: the spindle FRF output-error fit (examples/spindle/spindle.mdl on examples/spindle/data/frf_Fx.csv,
// 1151 frequencies x 3 channels, 16 candidate parameters of which 10 act on the x-direction data), with mbgen's
// estimator, against the same local fit in SciPy (bench/fit_spindle_scipy.py, least_squares with an analytic
// Jacobian) in the same run. Times, as medians of repeats:
//   - local:  one local Levenberg-Marquardt fit of the weighted residuals from the model's defaults (no
//             log-ratio search), the same problem SciPy solves: the fair comparison;
//   - single: FitOptions{starts = 1}: log-ratio search and refinement from the defaults (what `mbgen fit
//             --starts 1` does);
//   - multi:  the default global fit, FitOptions{} (16 starts on 2 threads).
// Prints wall-clock and process CPU times (on a loaded machine the CPU time is the fairer measure), the ratio
// SciPy / mbgen of the local fits, and the final costs (they must agree).
//
//   fit_spindle [REPEATS] [--no-scipy]   (run from anywhere; finds the model, data and script through
//                                         MBGEN_SOURCE_DIR; --no-scipy: mbgen's times only, e.g. for a profiler)
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"

#include "mbgen/data/data_set.hpp"
#include "mbgen/estimation/fit.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace {

using namespace mbgen;

struct Timed {
  double seconds = 0;  // median wall-clock time
  double cpu_seconds = 0;  // median process CPU time (both threads of the multi-start)
  FitResult result;
};

double cpu_now() { return double(std::clock()) / CLOCKS_PER_SEC; }

Timed time_fit(const Model& model, const DataSet& data, const FitOptions& options, int repeats) {
  std::vector<double> wall, cpu;
  Timed t;
  for (int i = 0; i < repeats; ++i) {
    const double c0 = cpu_now();
    const auto t0 = std::chrono::steady_clock::now();
    t.result = fit(model, {data}, options);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(cpu_now() - c0);
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  t.seconds = wall[wall.size() / 2];
  t.cpu_seconds = cpu[cpu.size() / 2];
  return t;
}

std::string run_command(const std::string& cmd) {
  std::string output;
  if (FILE* pipe = popen(cmd.c_str(), "r")) {
    char buf[4096];
    while (fgets(buf, sizeof buf, pipe)) output += buf;
    if (pclose(pipe) != 0) output.clear();
  }
  return output;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const bool scipy = !(argc > 2 && std::string(argv[2]) == "--no-scipy");
  const std::string source = MBGEN_SOURCE_DIR;
  const std::string mdl = source + "/examples/spindle/spindle.mdl", csv = source + "/examples/spindle/data/frf_Fx.csv";
  const auto model = evaluator::make_evaluator(frontend::parse_file(mdl));
  const DataSet data = read_data_file(csv);

  FitOptions local;
  local.starts = 1;
  local.log_search = false;
  FitOptions single;
  single.starts = 1;
  const Timed l = time_fit(*model, data, local, repeats);
  const Timed s = time_fit(*model, data, single, repeats);
  const Timed m = time_fit(*model, data, FitOptions{}, std::max(1, repeats / 2));

  // SciPy comes from the Debian package (python3-scipy): prefer /usr/bin/python3 over a python3 earlier in PATH
  // that may lack it; MBGEN_PYTHON overrides.
  const char* env_python = std::getenv("MBGEN_PYTHON");
  const std::string python = env_python ? env_python
                             : std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string cmd = "'" + python + "' '" + source + "/bench/fit_spindle_scipy.py' '" + csv + "' " +
                          std::to_string(repeats);
  const std::string output = scipy ? run_command(cmd) : std::string();

  std::printf("spindle FRF fit, %ld residuals, %zu estimated parameters (of %zu candidates); medians\n",
              l.result.residual_count, l.result.estimated.size(), l.result.parameters.size());
  std::printf("  mbgen local LM   : %.4f s wall, %.4f s CPU  cost %.10g  (%d LM iterations)\n", l.seconds,
              l.cpu_seconds, l.result.cost, l.result.iterations);
  std::printf("  mbgen 1 start    : %.4f s wall, %.4f s CPU  cost %.10g  (log-ratio search + refinement)\n", s.seconds,
              s.cpu_seconds, s.result.cost);
  std::printf("  mbgen 16 starts  : %.4f s wall, %.4f s CPU  cost %.10g  (best start %d)\n", m.seconds,
              m.cpu_seconds, m.result.cost, m.result.best_start);
  if (!scipy) return 0;
  if (output.empty()) {
    std::printf("  scipy            : failed to run %s\n", cmd.c_str());
    return 1;
  }
  const nlohmann::json j = nlohmann::json::parse(output);
  const double theirs = j["seconds"].get<double>(), theirs_cpu = j["cpu_seconds"].get<double>();
  std::printf("  scipy local      : %.4f s wall, %.4f s CPU  cost %.10g  (%d function evaluations)\n", theirs,
              theirs_cpu, j["cost"].get<double>(), j["nfev"].get<int>());
  std::printf("  ratio scipy / mbgen (local fits): %.1f wall, %.1f CPU\n", theirs / l.seconds, theirs_cpu / l.cpu_seconds);
  for (const auto& e : l.result.parameters)
    if (e.identifiable && j["values"].contains(e.name))
      std::printf("  %-6s mbgen %.8g  scipy %.8g\n", e.name.c_str(), e.value, j["values"][e.name].get<double>());
  return 0;
}
