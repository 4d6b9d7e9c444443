// SSI-cov on output-only records of drawn truths made by the independent truth generator (scripts/truthgen --kind
// oma): unmeasured white forces, responses only, 40 dB output noise. Seeds fixed before the results were seen.
#include "mbgen/output_only_modal.hpp"
#include "oma_truth.hpp"

#include <catch2/catch.hpp>

using namespace mbgen;

namespace {

void check_ssi(const std::string& example, int draw, int seed) {
  const test::OmaTruth t = test::oma_truth(example, draw, seed);
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
