// Benchmark: mbgen's symbolic derivation (derive() with transfer functions) of the spindle model against an
// independent SymPy Lagrange derivation of the same model (bench/derive_spindle_sympy.py), in the same run.
//
//   derive_spindle [--repeats N] [--sympy-repeats N] [--no-sympy]
//
// Prints the median wall time of each, their ratio, and the undamped natural frequencies both derivations give
// (they must agree: a benchmark of a wrong derivation is worthless).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "frontend/parser.hpp"
#include "natural_frequencies.hpp"
#include "symbolic/derive.hpp"

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

// Runs the SymPy script and returns its JSON line.
nlohmann::json run_sympy(int repeats) {
  const std::string command =
      "python3 " + std::string(MBGEN_SOURCE_DIR) + "/bench/derive_spindle_sympy.py " + std::to_string(repeats);
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::string out;
  char buf[4096];
  while (size_t got = fread(buf, 1, sizeof buf, pipe)) out.append(buf, got);
  if (pclose(pipe) != 0) throw std::runtime_error(command + " failed");
  return nlohmann::json::parse(out);
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 21, sympy_repeats = 3;
  bool sympy = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeats" && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
    } else if (a == "--sympy-repeats" && i + 1 < argc) {
      sympy_repeats = std::atoi(argv[++i]);
    } else if (a == "--no-sympy") {
      sympy = false;
    } else {
      std::cerr << "usage: derive_spindle [--repeats N] [--sympy-repeats N] [--no-sympy]\n";
      return 2;
    }
  }
  repeats = std::max(repeats, 1);
  sympy_repeats = std::max(sympy_repeats, 1);
  const mbgen::ir::ModelIr model =
      mbgen::frontend::parse_file(std::string(MBGEN_SOURCE_DIR) + "/examples/spindle/spindle.mdl");
  using clock = std::chrono::steady_clock;
  std::vector<double> with_tf, without_tf;
  size_t tf_count = 0, blocks = 0;
  std::vector<double> freqs;
  for (int r = 0; r < repeats; ++r) {
    auto t0 = clock::now();
    const mbgen::symbolic::SymbolicModel sm = mbgen::symbolic::derive(model);
    with_tf.push_back(std::chrono::duration<double>(clock::now() - t0).count());
    t0 = clock::now();
    const mbgen::symbolic::SymbolicModel bare = mbgen::symbolic::derive(model, {{}, false});
    without_tf.push_back(std::chrono::duration<double>(clock::now() - t0).count());
    if (r == 0) {
      tf_count = sm.transfer_functions.size();
      blocks = sm.blocks.size();
      freqs = mbgen::bench::natural_frequencies(sm);
    }
  }
  const double ours = median(with_tf);
  std::printf("spindle: %zu coordinates, %zu blocks, %zu transfer functions\n", freqs.size(), blocks, tf_count);
  std::printf("mbgen derive (M, C, K, B, outputs, checks, blocks):   median %8.2f ms over %d runs\n",
              1e3 * median(without_tf), repeats);
  std::printf("mbgen derive + transfer functions:                     median %8.2f ms over %d runs\n", 1e3 * ours,
              repeats);
  std::printf("mbgen natural frequencies [Hz]:");
  for (double f : freqs) std::printf(" %.2f", f);
  std::printf("\n");
  if (!sympy) return 0;
  const nlohmann::json s = run_sympy(sympy_repeats);
  const double theirs = s.at("median_s").get<double>();
  std::printf("SymPy Lagrange derivation + transfer functions:        median %8.2f ms over %d runs\n", 1e3 * theirs,
              sympy_repeats);
  std::printf("SymPy natural frequencies [Hz]:");
  double worst = 0;
  const auto& theirs_f = s.at("frequencies_hz");
  for (size_t i = 0; i < theirs_f.size(); ++i) {
    const double f = theirs_f[i].get<double>();
    std::printf(" %.2f", f);
    if (i < freqs.size()) worst = std::max(worst, std::fabs(f - freqs[i]) / freqs[i]);
  }
  std::printf("\nlargest relative difference of the frequencies: %.1e%s\n", worst,
              theirs_f.size() == freqs.size() && worst < 1e-6 ? "" : "  (DISAGREE)");
  std::printf("ratio SymPy / mbgen: %.0f\n", theirs / ours);
  return 0;
}
