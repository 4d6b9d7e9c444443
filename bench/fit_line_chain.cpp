// prototype
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "evaluator/symbolic_evaluator.hpp"
#include "evaluator/test_line_chain.hpp"
#include "frontend/parser.hpp"
#include "mbgen/fit.hpp"

using namespace mbgen;
namespace lc = mbgen::test::line_chain;

int main(int argc, char** argv) {
  int stages = 1, bodies = 33, every = 3, draw = 1, starts = 1, lines = 400, log_search = 1, threads = 1;
  double spread = 0.25, noise_rel = 0.01, fmin = 2, fmax = 400, stol = 1e-10;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const double v = std::atof(argv[i + 1]);
    if (a == "-n") bodies = int(v);
    else if (a == "-e") every = int(v);
    else if (a == "-d") draw = int(v);
    else if (a == "-s") starts = int(v);
    else if (a == "-l") lines = int(v);
    else if (a == "-g") log_search = int(v);
    else if (a == "-t") threads = int(v);
    else if (a == "-p") spread = v;
    else if (a == "-r") noise_rel = v;
    else if (a == "-fmin") fmin = v;
    else if (a == "-fmax") fmax = v;
    else if (a == "-c") stol = v;
    else if (a == "-k") stages = int(v);
  }
  const auto t_model0 = std::chrono::steady_clock::now();
  const ir::Model ir = frontend::parse_string(lc::model_text(bodies, every), "line_chain.mdl");
  const auto model = evaluator::make_evaluator(ir);
  const double t_model = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_model0).count();
  const ModelInfo& info = model->info();
  std::mt19937_64 rng(draw);
  std::uniform_real_distribution<double> factor(1 - spread, 1 + spread);
  std::vector<double> m(bodies), k(bodies), c(bodies);
  Eigen::VectorXd truth = info.default_values();
  for (int i = 0; i < bodies; ++i) {
    m[i] = lc::nominal_mass(i + 1) * factor(rng);
    k[i] = lc::nominal_stiffness(i + 1) * factor(rng);
    c[i] = lc::nominal_damping(i + 1) * factor(rng);
    truth[info.parameter_index("m" + std::to_string(i + 1))] = m[i];
    truth[info.parameter_index("k" + std::to_string(i + 1))] = k[i];
    truth[info.parameter_index("c" + std::to_string(i + 1))] = c[i];
  }
  const std::vector<int> sensors = lc::sensor_bodies(bodies, every);
  FrfData data;
  data.file = "line chain (synthetic)";
  data.f_hz.resize(lines);
  for (int j = 0; j < lines; ++j) data.f_hz[j] = fmin * std::pow(fmax / fmin, double(j) / (lines - 1));
  const double g2 = 1 / (1 + noise_rel * noise_rel);
  std::normal_distribution<double> noise(0.0, noise_rel / std::sqrt(2.0));
  for (int b : sensors) {
    FrfChannel ch;
    ch.output = lc::output_name(b);
    ch.input = "F";
    ch.values.resize(lines);
    ch.coherence = Eigen::VectorXd::Constant(lines, g2);
    data.channels.push_back(ch);
  }
  for (int j = 0; j < lines; ++j) {
    const auto h = lc::accelerance(m, k, c, sensors, data.f_hz[j]);
    for (std::size_t s = 0; s < sensors.size(); ++s)
      data.channels[s].values[j] = h[s] * std::complex<double>(1 + noise(rng), noise(rng));
  }
  FitOptions o;
  o.starts = starts;
  o.threads = threads;
  if (std::getenv("SSPREAD")) o.spread = std::atof(std::getenv("SSPREAD"));
  o.log_search = log_search != 0;
  o.frf_weighting.floor = 1e-9;
  o.search_cost_tolerance = stol;
  if (std::getenv("PROGRESS"))
    o.progress = [](const FitProgress& p) {
      std::fprintf(stderr, "  %s s%d %d: cost %.6g\n", p.stage.c_str(), p.start, p.iteration, p.cost);
    };
  const double c0 = double(std::clock()) / CLOCKS_PER_SEC;
  const auto t0 = std::chrono::steady_clock::now();
  FitResult r;
  for (int st = 1; st <= stages; ++st) {
    const double hi = fmin * std::pow(fmax / fmin, double(st) / stages);
    r = fit(*model, {DataSet(within_band(data, 0, hi * 1.0001))}, o);
    for (std::size_t i = 0; i < info.parameters.size(); ++i) o.values[info.parameters[i].name] = r.values[Eigen::Index(i)];
    if (std::getenv("STAGES")) std::fprintf(stderr, "stage %d to %.1f Hz: iter %d est %zu nrmse %.4g\n", st, hi, r.iterations, r.estimated.size(), r.nrmse);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = double(std::clock()) / CLOCKS_PER_SEC - c0;
  double worst = 0, worst_z = 0;
  for (const auto& p : r.parameters) {
    const int i = info.parameter_index(p.name);
    worst = std::max(worst, std::fabs(p.value / truth[i] - 1));
    if (p.std > 0) worst_z = std::max(worst_z, std::fabs(p.value - truth[i]) / p.std);
  }
  double prior_worst = 0;
  for (int i = 0; i < truth.size(); ++i) prior_worst = std::max(prior_worst, std::fabs(info.parameters[i].value / truth[i] - 1));
  std::printf("N=%d params=%zu rows=%ld model %.2fs fit wall %.2f cpu %.2f iter %d est %zu nrmse %.4g maxerr %.3g (prior %.3g) max|z| %.2f %s\n",
              bodies, info.parameters.size(), r.residual_count, t_model, wall, cpu, r.iterations, r.estimated.size(),
              r.nrmse, worst, prior_worst, worst_z, r.stop_reason.c_str());
  if (r.singular_values.size()) std::printf("  sv ratio %.3g\n", r.singular_values.tail(1)[0] / r.singular_values[0]);
  if (std::getenv("VERBOSE"))
    for (const auto& p : r.parameters) {
      const int i = info.parameter_index(p.name);
      std::printf("  %-5s truth %12.5g est %12.5g std %10.3g err %8.4f z %6.2f%s\n", p.name.c_str(), truth[i], p.value, p.std,
                  p.value / truth[i] - 1, p.std > 0 ? (p.value - truth[i]) / p.std : 0.0, p.identifiable ? "" : " (not id)");
    }
  return 0;
}
