// FDD and EFDD on output-only records of drawn truths made by the independent truth generator (scripts/truthgen
// --kind oma): unmeasured white forces, responses only, 40 dB output noise. Seeds fixed before the results were
// seen (the same records as ssi_cov_test).
#include "mbgen/output_only_modal.hpp"
#include "oma_truth.hpp"

#include <catch2/catch.hpp>

using namespace mbgen;

namespace {

void check_fdd(const std::string& example, int draw, int seed) {
  const test::OmaTruth t = test::oma_truth(example, draw, seed);
  OutputOnlyOptions options;
  options.method = OutputOnlyMethod::Fdd;
  const OutputOnlyIdentification r = identify_output_only(t.data, options);
  CHECK(r.method == OutputOnlyMethod::Fdd);
  CHECK(r.fdd.singular.cols() == static_cast<Eigen::Index>(t.data.channels.size()));
  test::check_against_truth(r.modes, t.modes);
}

}  // namespace

TEST_CASE("FDD: mdof2 draw 1", "[fdd]") { check_fdd("mdof2", 1, 11); }
TEST_CASE("FDD: mdof2 draw 2", "[fdd]") { check_fdd("mdof2", 2, 12); }
TEST_CASE("FDD: spindle draw 1", "[fdd]") { check_fdd("spindle", 1, 21); }
TEST_CASE("FDD: spindle draw 2", "[fdd]") { check_fdd("spindle", 2, 22); }
// Draws 3 and 4 were held out for the choice of OutputOnlyOptions::min_contribution (set on draws 1 and 2); spindle
// draw 4 then failed (a spurious 196 Hz pole of 9 orders), and the selection was raised to half the orders.
TEST_CASE("FDD: mdof2 draw 3", "[fdd]") { check_fdd("mdof2", 3, 13); }
TEST_CASE("FDD: mdof2 draw 4", "[fdd]") { check_fdd("mdof2", 4, 14); }
TEST_CASE("FDD: spindle draw 3", "[fdd]") { check_fdd("spindle", 3, 23); }
TEST_CASE("FDD: spindle draw 4", "[fdd]") { check_fdd("spindle", 4, 24); }
// Held out for both choices (min_contribution, half the orders): drawn after them.
TEST_CASE("FDD: mdof2 draw 5", "[fdd]") { check_fdd("mdof2", 5, 15); }
TEST_CASE("FDD: mdof2 draw 6", "[fdd]") { check_fdd("mdof2", 6, 16); }
TEST_CASE("FDD: spindle draw 5", "[fdd]") { check_fdd("spindle", 5, 25); }
TEST_CASE("FDD: spindle draw 6", "[fdd]") { check_fdd("spindle", 6, 26); }
