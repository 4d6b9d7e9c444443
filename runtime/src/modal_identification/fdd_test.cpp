// FDD and EFDD on output-only records of drawn truths made by the independent truth generator (scripts/truthgen
// --kind oma): unmeasured white forces, responses only, 40 dB output noise; the same records as ssi_cov_test, seeds
// fixed before the results were seen.
//
// What meets issue 34's targets and what does not (docs/modal.md, "Output-only modal analysis"): every frequency
// within 1 % (at most 0.35 % off on draws 1-6) and no spurious peak, and the shapes of mdof2, pass. Known to miss:
// EFDD's damping, 25 % to 50 % high for the weaker modes and mdof2's very light first mode (zeta 0.0005), and the
// spindle's second mode's shape (MAC 0.925 to 0.953: its one force drives all modes coherently, so the first
// singular vector at the weaker mode's peak holds some of the strong neighbour's). Those are checked in the
// [!mayfail] cases below, which report them without failing the suite.
#include "mbgen/output_only_modal.hpp"
#include "oma_truth.hpp"

#include <catch2/catch.hpp>

using namespace mbgen;

namespace {

OutputOnlyIdentification run_fdd(const test::OmaTruth& t) {
  OutputOnlyOptions options;
  options.method = OutputOnlyMethod::Fdd;
  const OutputOnlyIdentification r = identify_output_only(t.data, options);
  CHECK(r.method == OutputOnlyMethod::Fdd);
  CHECK(r.fdd.singular.cols() == static_cast<Eigen::Index>(t.data.channels.size()));
  for (const FddPeak& p : r.fdd.peaks)
    UNSCOPED_INFO("peak " << p.f_hz << " Hz, bell " << p.bell_lines << " lines, EFDD " << p.efdd_f_hz << " Hz, zeta "
                          << p.zeta << (p.note.empty() ? "" : ": ") << p.note);
  return r;
}

// Frequencies and no spurious peak; with `shapes` also MAC > 0.95.
void check_fdd(const std::string& example, int draw, int seed, bool shapes) {
  const test::OmaTruth t = test::oma_truth("fdd_truth", example, draw, seed);
  test::Targets targets;
  targets.damping = false;
  targets.shape = shapes;
  test::check_against_truth(run_fdd(t).modes, t.modes, targets);
}

// Every target, damping by EFDD included.
void check_all_targets(const std::string& example, int draw, int seed) {
  const test::OmaTruth t = test::oma_truth("fdd_truth_all", example, draw, seed);
  test::check_against_truth(run_fdd(t).modes, t.modes);
}

}  // namespace

TEST_CASE("FDD: mdof2 frequencies and shapes", "[fdd]") {
  for (int draw = 1; draw <= 6; ++draw) check_fdd("mdof2", draw, 10 + draw, true);
}
TEST_CASE("FDD: spindle frequencies", "[fdd]") {
  for (int draw = 1; draw <= 6; ++draw) check_fdd("spindle", draw, 20 + draw, false);
}
TEST_CASE("FDD: mdof2 all targets, EFDD damping included (known to miss)", "[fdd][!mayfail]") {
  for (int draw = 1; draw <= 6; ++draw) check_all_targets("mdof2", draw, 10 + draw);
}
TEST_CASE("FDD: spindle all targets, EFDD damping included (known to miss)", "[fdd][!mayfail]") {
  for (int draw = 1; draw <= 6; ++draw) check_all_targets("spindle", draw, 20 + draw);
}
