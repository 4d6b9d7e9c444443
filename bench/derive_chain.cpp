// Benchmark: derive + emit at machine scale (issue 14). A chain of N six-coordinate bodies, each held to the
// previous one by three 3-D spring-dampers (compiler/symbolic/test_chain_model.hpp), for N = 8, 16, 32, 64, 100:
//
//   derive_chain [--max N] [--sympy [--sympy-timeout S]] [N...]
//
// For each N: the wall time and peak memory of the command `mbgen MODEL.mdl -o OUT.cpp` (a child process, so its
// peak resident set is its own), and in this process the stages: parse, derive without transfer functions,
// transfer functions, emit. Then the growth exponent of the command's time, a least-squares fit of
// log t = a + b log N over the sizes run (the ratio of times within one run, so the machine's load affects it less
// than the absolute times).
//
// With --sympy, then for N = 1, 2, 4, 8, ... (up to the largest N above): the independent SymPy derivation
// bench/derive_chain_sympy.py (M, C, K, B, outputs by Lagrange's equations; a child process, stopped after S
// seconds, default 600; larger sizes are not tried once one is stopped) beside mbgen's derivation of the same
// matrices (derive without transfer functions, in process) and the command, the natural frequencies of both
// compared (they must agree), and the growth exponents of both over the sizes SymPy finished.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "emit/cpp_emitter.hpp"
#include "frontend/parser.hpp"
#include "natural_frequencies.hpp"
#include "seconds_since.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/test_chain_model.hpp"
#include "symbolic/transfer_functions.hpp"

namespace {

using mbgen::bench::seconds_since;

struct CommandRun {
  double seconds = 0;
  long peak_kb = 0;
  int status = -1;
};

CommandRun run_command(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  CommandRun r;
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  r.seconds = seconds_since(t0);
  r.peak_kb = usage.ru_maxrss;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

double growth(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < x.size(); ++k) mx += x[k] / static_cast<double>(x.size()), my += y[k] / static_cast<double>(x.size());
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < x.size(); ++k) sxy += (x[k] - mx) * (y[k] - my), sxx += (x[k] - mx) * (x[k] - mx);
  return sxy / sxx;
}

// SymPy beside mbgen for N = 1, 2, 4, ... <= max_n (see the top of the file).
void compare_with_sympy(int max_n, int timeout_s, const std::string& dir) {
  std::printf("\nSymPy's Lagrange derivation of M, C, K, B, outputs (bench/derive_chain_sympy.py, stopped after %d s)\n"
              "beside mbgen's derivation of the same (derive, no transfer functions) and the whole command:\n\n", timeout_s);
  std::printf("%5s %5s | %10s %10s %10s | %9s | %s\n", "N", "DOF", "SymPy [s]", "derive [s]", "command [s]", "ratio",
              "frequencies");
  std::vector<double> log_n, log_sympy, log_derive;
  for (int n = 1; n <= max_n; n *= 2) {
    const std::string model_file = dir + "/chain" + std::to_string(n) + ".mdl";
    const std::string text = mbgen::symbolic::test::chain_model_text(n);
    std::ofstream(model_file) << text;
    const CommandRun cmd = run_command({MBGEN_COMMAND, model_file, "-o", dir + "/chain_model.cpp"});
    const mbgen::ir::ModelIr model = mbgen::frontend::parse_string(text, model_file);
    const auto t0 = std::chrono::steady_clock::now();
    const mbgen::symbolic::SymbolicModel sm = mbgen::symbolic::derive(model, {{}, false});
    const double derive = seconds_since(t0);
    const std::vector<double> ours = mbgen::bench::natural_frequencies(sm);
    const std::string command = "timeout " + std::to_string(timeout_s) + " python3 " MBGEN_SOURCE_DIR
                                "/bench/derive_chain_sympy.py " + std::to_string(n);
    std::string out;
    char buf[4096];
    FILE* pipe = popen(command.c_str(), "r");
    while (pipe) {
      const size_t got = fread(buf, 1, sizeof buf, pipe);
      if (got == 0) break;
      out.append(buf, got);
    }
    const int raw = pipe ? pclose(pipe) : -1;
    const int status = raw >= 0 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    if (status != 0 || out.empty()) {
      std::printf("%5d %5d | %10s %10.3f %10.2f | %9s | %s\n", n, 6 * n, "-", derive, cmd.seconds, "-",
                  status == 124 ? ("SymPy stopped after " + std::to_string(timeout_s) + " s").c_str()
                                : ("SymPy failed (exit status " + std::to_string(status) + ")").c_str());
      break;
    }
    const nlohmann::json s = nlohmann::json::parse(out);
    const double theirs = s.at("seconds").get<double>();
    double worst = 0;
    const auto& f = s.at("frequencies_hz");
    for (std::size_t i = 0; i < f.size() && i < ours.size(); ++i)
      worst = std::max(worst, std::fabs(f[i].get<double>() - ours[i]) / ours[i]);
    const bool agree = f.size() == ours.size() && worst < 1e-6;
    std::printf("%5d %5d | %10.2f %10.3f %10.2f | %9.0f | largest relative difference %.1e%s\n", n, 6 * n, theirs,
                derive, cmd.seconds, theirs / derive, worst, agree ? "" : "  (DISAGREE)");
    std::fflush(stdout);
    log_n.push_back(std::log(static_cast<double>(n)));
    log_sympy.push_back(std::log(theirs));
    log_derive.push_back(std::log(derive));
  }
  if (log_n.size() >= 2)
    std::printf("\ngrowth over N = 1..%d: SymPy t ~ N^%.2f, mbgen derive t ~ N^%.2f\n",
                static_cast<int>(std::lround(std::exp(log_n.back()))), growth(log_n, log_sympy), growth(log_n, log_derive));
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  int max = 100, sympy_timeout = 600;
  bool sympy = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--max" && i + 1 < argc)
      max = std::atoi(argv[++i]);
    else if (a == "--sympy")
      sympy = true;
    else if (a == "--sympy-timeout" && i + 1 < argc)
      sympy_timeout = std::atoi(argv[++i]);
    else if (std::atoi(a.c_str()) > 0)
      sizes.push_back(std::atoi(a.c_str()));
    else {
      std::cerr << "usage: derive_chain [--max N] [--sympy [--sympy-timeout S]] [N...]\n";
      return 2;
    }
  }
  if (sizes.empty())
    for (int n : {8, 16, 32, 64, 100})
      if (n <= max) sizes.push_back(n);
  char dir_template[] = "/tmp/derive_chain_XXXXXX";
  const std::string dir = mkdtemp(dir_template);

  std::printf("chain of N six-coordinate bodies (6N coordinates, one block), 1 input, 2 outputs; exact transfer-function\n"
              "coefficients for blocks of up to %d coordinates\n\n", mbgen::symbolic::kMaxExactBlockSize);
  std::printf("%5s %5s | %9s %9s | %8s %9s %9s %8s\n", "N", "DOF", "command", "peak", "parse", "derive", "TFs", "emit");
  std::printf("%5s %5s | %9s %9s | %8s %9s %9s %8s\n", "", "", "[s]", "[MB]", "[s]", "[s]", "[s]", "[s]");
  std::vector<double> log_n, log_t;
  for (int n : sizes) {
    const std::string model_file = dir + "/chain" + std::to_string(n) + ".mdl";
    const std::string text = mbgen::symbolic::test::chain_model_text(n);
    std::ofstream(model_file) << text;
    const CommandRun cmd = run_command({MBGEN_COMMAND, model_file, "-o", dir + "/chain_model.cpp"});
    if (cmd.status != 0) {
      std::fprintf(stderr, "mbgen failed on N = %d (status %d)\n", n, cmd.status);
      return 1;
    }
    auto t0 = std::chrono::steady_clock::now();
    const mbgen::ir::ModelIr model = mbgen::frontend::parse_string(text, model_file);
    const double parse = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    mbgen::symbolic::SymbolicModel sm = mbgen::symbolic::derive(model, {{}, false});
    const double derive = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    mbgen::symbolic::add_transfer_functions(sm);
    const double tfs = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    mbgen::emit::CppEmitOptions options;
    options.header_file = "chain_model.hpp";
    options.source_file = "chain_model.cpp";
    const mbgen::emit::CppEmitResult emitted = mbgen::emit::emit_cpp(sm, options);
    const double emit = seconds_since(t0);
    std::printf("%5d %5d | %9.2f %9.1f | %8.3f %9.3f %9.3f %8.3f   (%zu bytes emitted)\n", n, 6 * n, cmd.seconds,
                static_cast<double>(cmd.peak_kb) / 1024.0, parse, derive, tfs, emit,
                emitted.header.size() + emitted.source.size());
    std::fflush(stdout);
    log_n.push_back(std::log(static_cast<double>(n)));
    log_t.push_back(std::log(cmd.seconds));
  }
  if (log_n.size() >= 2) {
    double mn = 0, mt = 0;
    for (std::size_t k = 0; k < log_n.size(); ++k) mn += log_n[k] / static_cast<double>(log_n.size()), mt += log_t[k] / static_cast<double>(log_n.size());
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < log_n.size(); ++k) sxy += (log_n[k] - mn) * (log_t[k] - mt), sxx += (log_n[k] - mn) * (log_n[k] - mn);
    std::printf("\ngrowth of the command's time: t ~ N^%.2f (least squares over N = %d..%d)\n", sxy / sxx, sizes.front(),
                sizes.back());
    // The last two sizes alone: the local exponent where the cost is highest.
    const std::size_t k = log_n.size() - 1;
    std::printf("local exponent between the two largest sizes: %.2f\n",
                (log_t[k] - log_t[k - 1]) / (log_n[k] - log_n[k - 1]));
  }
  if (sympy) compare_with_sympy(sizes.back(), sympy_timeout, dir);
  std::system(("rm -rf " + dir).c_str());
  return 0;
}
