// modal_frf_matrix: `mbgen modal`'s analysis (identify_modes) on a 9-channel, 4096-line FRF matrix: 3 outputs x 3
// inputs (poly-reference, 3 references) and the same 9 channels as 9 rows of one reference (common-denominator
// LSCF), twelve modes in the band with a close pair and a weak mode, 1 % noise. Prints the median wall time of
// each stage over N runs (default 5) and the modes found. `modal_frf_matrix --write FILE.csv` writes the FRFs
// instead, for timing the command itself. See README.md.
#include "mbgen/data/csv.hpp"
#include "mbgen/modal_identification/modal_identification.hpp"
#include "mbgen_test/synthetic_frf.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace {

using Clock = std::chrono::steady_clock;

double ms(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

mbgen::test::SyntheticFrfSpec spec() {
  mbgen::test::SyntheticFrfSpec s;
  const double f[] = {35, 80, 83, 140, 210, 260, 330, 395, 470, 520, 610, 700};
  const double zeta[] = {0.02, 0.01, 0.012, 0.008, 0.015, 0.01, 0.02, 0.006, 0.01, 0.012, 0.009, 0.015};
  for (int r = 0; r < 12; ++r) {
    mbgen::test::TrueMode m{f[r], zeta[r], {}};
    for (int p = 0; p < 6; ++p) m.shape.push_back(std::sin((r + 1) * (p + 0.7) * 0.45));  // beam-like shapes
    if (r == 7)
      for (double& x : m.shape) x *= 0.15;  // a weak mode
    s.modes.push_back(m);
  }
  s.output_points = {0, 2, 4};
  s.input_points = {1, 3, 5};
  s.f_lo = 5;
  s.f_hi = 800;
  s.lines = 4096;
  s.noise = 0.01;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const mbgen::FrfData frf = mbgen::test::synthetic_frf(spec(), "bench");
  if (argc > 2 && std::string(argv[1]) == "--write") {
    std::ofstream out(argv[2]);
    mbgen::write_frf_csv(out, frf);
    return out ? 0 : 1;
  }
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  for (const bool poly : {true, false}) {
    std::vector<double> t_data, t_lscf, t_select, t_refine, t_lsfd, t_total;
    mbgen::ModalIdentification last;
    for (int k = 0; k < repeats; ++k) {
      const auto t0 = Clock::now();
      const mbgen::ModalData data = mbgen::modal_data({frf}, {}, mbgen::FrfQuantity::Receptance);
      const auto t1 = Clock::now();
      mbgen::LscfOptions lscf;
      lscf.poly_reference = poly;
      mbgen::StabilizationDiagram diagram = mbgen::lscf(data, lscf);
      const auto t2 = Clock::now();
      mbgen::label_stability(diagram);
      const std::vector<mbgen::SelectedPole> poles = mbgen::select_physical_poles(diagram);
      const auto t3 = Clock::now();
      std::vector<std::complex<double>> lambdas;
      for (const auto& p : poles) lambdas.push_back(p.lambda);
      const mbgen::RefinedPoles refined = mbgen::refine_poles(data, lambdas);
      const auto t4 = Clock::now();
      const mbgen::LsfdResult fit = mbgen::lsfd(data, refined.poles);
      const auto t5 = Clock::now();
      mbgen::ModalOptions options;
      options.lscf.poly_reference = poly;
      last = mbgen::identify_modes(data, options);  // the whole pipeline, as the command runs it
      const auto t6 = Clock::now();
      t_data.push_back(ms(t0, t1));
      t_lscf.push_back(ms(t1, t2));
      t_select.push_back(ms(t2, t3));
      t_refine.push_back(ms(t3, t4));
      t_lsfd.push_back(ms(t4, t5));
      t_total.push_back(ms(t5, t6) + ms(t0, t1));
      (void)fit;
    }
    std::printf("%s: 9 channels x 4096 lines, %d references, orders 1..%d, %zu poles in the diagram\n",
                poly ? "poly-reference LSCF (3 x 3)" : "common-denominator LSCF (9 rows)", last.diagram.references,
                last.diagram.orders.back(), last.diagram.poles.size());
    std::printf(
        "  median of %d runs: data %.1f ms, LSCF %.1f ms, stabilization + selection %.1f ms, refinement %.1f ms, "
        "LSFD %.1f ms; identify_modes in all %.1f ms\n",
        repeats, median(t_data), median(t_lscf), median(t_select), median(t_refine), median(t_lsfd), median(t_total));
    std::printf("  %zu modes:", last.modes.size());
    for (const auto& m : last.modes) std::printf(" %.2f", m.f_hz);
    std::printf(" Hz (true: 35 80 83 140 210 260 330 395 470 520 610 700)\n");
  }
  return 0;
}
