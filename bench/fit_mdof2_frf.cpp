// Benchmark: mdof2 FRF output-error fit (local Levenberg-Marquardt from a prior 2-20 % off) with mbgen's estimator
// against the same fit in SciPy (bench/fit_scipy.py, least_squares 'lm' with an analytic Jacobian), in the same
// run. Prints both times (median of repeats), the ratio, and both final costs (they must agree).
//
//   fit_mdof2_frf [REPEATS]     (run from anywhere; finds fit_scipy.py through MBGEN_SOURCE_DIR)
#include "mbgen_test/estimation.hpp"

#include "mbgen/data/csv.hpp"
#include "mbgen/estimation/fit.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

int main(int argc, char** argv) {
  using namespace mbgen;
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const test::Mdof2Values truth;
  std::mt19937 rng(42);
  const FrfData data = test::mdof2_frf_data(truth, Eigen::VectorXd::LinSpaced(2241, 20, 300), 0.01, rng);
  test::Mdof2Values prior = truth;
  // Close enough to the optimum that a plain local LM converges (lightly damped peaks make the cost multimodal:
  // from farther away SciPy's local fit stops in a wrong minimum; mbgen's global search is not timed here).
  prior.m1 *= 1.02; prior.m2 *= 0.98; prior.k11 *= 1.03; prior.k22 *= 0.97; prior.k12 *= 1.03;
  prior.c11 *= 0.8; prior.c22 *= 1.2;
  const test::LinearModel model = test::mdof2_model(prior);

  FitOptions options;
  options.starts = 1;         // a local fit: what SciPy's least_squares does
  options.log_search = false;  // no log-ratio search stage: the same cost function throughout
  std::vector<double> times;
  FitResult result;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    result = fit(model, {DataSet(data)}, options);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(times.begin(), times.end());
  const double ours = times[times.size() / 2];

  const std::filesystem::path csv = std::filesystem::temp_directory_path() / "mbgen_bench_fit_mdof2.csv";
  {
    std::ofstream out(csv);
    write_frf_csv(out, data);
  }
  std::ostringstream prior_json;
  prior_json.precision(17);
  prior_json << "[" << prior.m1 << "," << prior.m2 << "," << prior.k11 << "," << prior.k22 << "," << prior.k12 << ","
             << prior.c11 << "," << prior.c22 << "]";
  // SciPy comes from the Debian package (python3-scipy): prefer /usr/bin/python3 over a python3 earlier in PATH
  // that may lack it; MBGEN_PYTHON overrides.
  const char* env_python = std::getenv("MBGEN_PYTHON");
  const std::string python = env_python ? env_python
                             : std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string cmd = "'" + python + "' '" + std::string(MBGEN_SOURCE_DIR) + "/bench/fit_scipy.py' '" + csv.string() +
                          "' '" + prior_json.str() + "' " + std::to_string(repeats);
  std::string output;
  if (FILE* pipe = popen(cmd.c_str(), "r")) {
    char buf[4096];
    while (fgets(buf, sizeof buf, pipe)) output += buf;
    if (pclose(pipe) != 0) output.clear();
  }
  std::filesystem::remove(csv);
  std::printf("mdof2 FRF fit, %ld residuals, 7 parameters, median of %d\n", result.residual_count, repeats);
  std::printf("  mbgen : %.4f s  cost %.10g  (%d LM iterations)\n", ours, result.cost, result.iterations);
  if (output.empty()) {
    std::printf("  scipy : failed to run %s\n", cmd.c_str());
    return 1;
  }
  const nlohmann::json s = nlohmann::json::parse(output);
  const double theirs = s["seconds"].get<double>();
  std::printf("  scipy : %.4f s  cost %.10g  (%d function evaluations)\n", theirs, s["cost"].get<double>(),
              s["nfev"].get<int>());
  std::printf("  ratio scipy / mbgen = %.2f\n", theirs / ours);
  for (const auto& e : result.parameters)
    std::printf("  %-4s mbgen %.8g  scipy %.8g\n", e.name.c_str(), e.value, s["values"][e.name].get<double>());
  return 0;
}
