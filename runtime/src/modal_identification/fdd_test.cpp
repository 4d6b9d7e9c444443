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
