// SSI-cov on output-only records of drawn truths made by the independent truth generator (scripts/truthgen --kind
// oma): unmeasured white forces, responses only, 40 dB output noise. Seeds fixed before the results were seen.
#include "mbgen/modal_identification/output_only_modal.hpp"
#include "oma_truth.hpp"

#include <catch2/catch.hpp>

using namespace mbgen;

namespace {

void check_ssi(const std::string& example, int draw, int seed) {
  const test::OmaTruth t = test::oma_truth("ssi_cov_truth", example, draw, seed);
  const OutputOnlyIdentification r = identify_output_only(t.data);
  CHECK(r.method == OutputOnlyMethod::SsiCov);
  CHECK(r.ssi.diagram.orders.size() == 24);  // orders 2..48
  test::check_against_truth(r.modes, t.modes);
}

}  // namespace

TEST_CASE("SSI-cov: mdof2 draw 1", "[ssi-cov]") { check_ssi("mdof2", 1, 11); }
TEST_CASE("SSI-cov: mdof2 draw 2", "[ssi-cov]") { check_ssi("mdof2", 2, 12); }
TEST_CASE("SSI-cov: spindle draw 1", "[ssi-cov]") { check_ssi("spindle", 1, 21); }
TEST_CASE("SSI-cov: spindle draw 2", "[ssi-cov]") { check_ssi("spindle", 2, 22); }
// Draws 3 and 4 were held out for the choice of OutputOnlyOptions::min_contribution (set on draws 1 and 2); spindle
// draw 4 then failed (a spurious 196 Hz pole of 9 orders), and the selection was raised to half the orders.
TEST_CASE("SSI-cov: mdof2 draw 3", "[ssi-cov]") { check_ssi("mdof2", 3, 13); }
TEST_CASE("SSI-cov: mdof2 draw 4", "[ssi-cov]") { check_ssi("mdof2", 4, 14); }
TEST_CASE("SSI-cov: spindle draw 3", "[ssi-cov]") { check_ssi("spindle", 3, 23); }
TEST_CASE("SSI-cov: spindle draw 4", "[ssi-cov]") { check_ssi("spindle", 4, 24); }
// Held out for both choices (min_contribution, half the orders): drawn after them.
TEST_CASE("SSI-cov: mdof2 draw 5", "[ssi-cov]") { check_ssi("mdof2", 5, 15); }
TEST_CASE("SSI-cov: mdof2 draw 6", "[ssi-cov]") { check_ssi("mdof2", 6, 16); }
TEST_CASE("SSI-cov: spindle draw 5", "[ssi-cov]") { check_ssi("spindle", 5, 25); }
TEST_CASE("SSI-cov: spindle draw 6", "[ssi-cov]") { check_ssi("spindle", 6, 26); }
