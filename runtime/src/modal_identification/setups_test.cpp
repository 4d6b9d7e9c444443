// Two setups of roving sensors with one shared reference, merged: the spindle's three sensors measured as (xs_front,
// xs_rear) in one record and (xs_rear, xh_front) in another (each cut from its own truthgen --kind oma record,
// another noise seed), SSI-cov per setup, shapes glued on xs_rear. Seeds fixed before the results were seen.
#include "mbgen/modal_identification/output_only_modal.hpp"
#include "oma_truth.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

using namespace mbgen;

namespace {

TimeRecord without(TimeRecord r, const std::string& name) {
  r.signals.erase(std::remove_if(r.signals.begin(), r.signals.end(), [&](const Signal& s) { return s.name == name; }),
                  r.signals.end());
  return r;
}

void check_setups(int draw, int seed_a, int seed_b) {
  const test::OmaRecord a = test::oma_record("setups_truth", "spindle", draw, seed_a);
  const test::OmaRecord b = test::oma_record("setups_truth", "spindle", draw, seed_b);
  const std::vector<ResponseData> setups =
      response_setups({without(a.record, "xh_front"), without(b.record, "xs_front")});
  REQUIRE(setups.size() == 2);
  REQUIRE(setups[0].references == std::vector<int>{1});  // xs_rear, in (xs_front, xs_rear)
  REQUIRE(setups[1].references == std::vector<int>{0});  // xs_rear, in (xs_rear, xh_front)
  const MergedSetups m = identify_setups(setups);
  REQUIRE(m.data.channels == std::vector<std::string>{"xs_front", "xs_rear", "xh_front"});  // the truth's order
  test::check_against_truth(m.result.modes, a.modes);
}

}  // namespace

TEST_CASE("setups merged: spindle draw 1", "[setups]") { check_setups(1, 41, 42); }
TEST_CASE("setups merged: spindle draw 2", "[setups]") { check_setups(2, 43, 44); }

TEST_CASE("setups that share no response are refused", "[setups]") {
  TimeRecord a, b;
  a.file = "a.csv";
  b.file = "b.csv";
  a.t = b.t = Eigen::VectorXd::LinSpaced(300, 0.0, 0.299);
  a.signals = {{"x", Eigen::VectorXd::Random(300)}, {"y", Eigen::VectorXd::Random(300)}};
  b.signals = {{"u", Eigen::VectorXd::Random(300)}, {"v", Eigen::VectorXd::Random(300)}};
  CHECK_THROWS_WITH(response_setups({a, b}), Catch::Contains("b.csv") && Catch::Contains("share none"));
  CHECK_THROWS_WITH(response_setups({a, b}, {{}, {"x"}}), Catch::Contains("b.csv") && Catch::Contains("reference x"));
}
