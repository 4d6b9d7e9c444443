// The monitoring loop on mdof2 FRFs from the closed-form transfer functions (tests/support/mbgen_test/estimation.hpp), 40 dB:
// no alarm on scatter, one change naming the stepped parameter, a structural change when the truth leaves the model.
#include "mbgen_test/estimation.hpp"

#include "mbgen/monitoring/change_detection.hpp"
#include "mbgen/monitoring/monitor.hpp"
#include "mbgen/monitoring/monitor_report.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

using namespace mbgen;

namespace {

Eigen::VectorXd frequencies() { return Eigen::VectorXd::LinSpaced(1121, 20, 300); }  // 0.25 Hz steps

// Data sets of the truth `v` from set `from` on (before: the default truth), different noise each.
std::vector<DataSet> series(int count, int from, const test::Mdof2Values& changed) {
  std::vector<DataSet> out;
  std::mt19937 rng(11);
  for (int i = 0; i < count; ++i) {
    FrfData d = test::mdof2_frf_data(i < from ? test::Mdof2Values{} : changed, frequencies(), 0.01, rng);
    d.file = "set" + std::to_string(i) + ".csv";
    out.emplace_back(std::move(d));
  }
  return out;
}

MonitorOptions quick() {
  MonitorOptions o;
  o.fit.starts = 2;
  o.warm_starts = 2;
  return o;
}

}  // namespace

TEST_CASE("monitor: a stiffness step is one change naming it, scatter alone none", "[monitor]") {
  const test::LinearModel model = test::mdof2_model();
  test::Mdof2Values stepped;
  stepped.k22 *= 0.9;
  const std::vector<DataSet> data = series(7, 4, stepped);
  const MonitorResult r = monitor(model, data, std::vector<std::optional<std::string>>(7), quick());
  REQUIRE(r.series.size() == 7);
  CHECK(r.parameters.size() == 7);
  // The stated rate (one false alarm in 1000 sets) split between the CUSUMs and the single-set limit.
  CHECK(r.h == Approx(scheme_threshold(0.5, 2000, 7)));
  CHECK(r.single_set_limit == Approx(single_set_limit(2000, 7)));
  REQUIRE(r.changes.size() == 1);
  CHECK(r.changes[0].index == 4);
  CHECK(r.changes[0].onset == 4);
  CHECK(r.changes[0].parameters == std::vector<std::string>{"k22"});
  CHECK(r.changes[0].direction.at("k22") == -1);
  CHECK_FALSE(r.changes[0].structural);
  // No alarm before the step: every statistic below h there.
  for (int i = 3; i < 4; ++i)
    for (const auto& [name, s] : r.series[static_cast<std::size_t>(i)].cusum_up) CHECK(s < r.h);

  const nlohmann::json j = nlohmann::json::parse(monitor_result_json(r));
  CHECK(j["schema"] == "mbgen-monitor/1");
  CHECK(j["series"].size() == 7);
  CHECK(j["series"][0]["time"].is_null());
  CHECK(j["series"][5]["parameters"]["k22"].contains("shift"));
  CHECK(j["changes"][0]["index"] == 4);
  CHECK(j["changes"][0]["parameters"] == nlohmann::json::array({"k22"}));
  CHECK(j["changes"][0]["cause"].is_null());
}

TEST_CASE("monitor: a damper the model fixes at zero is a structural change", "[monitor]") {
  const test::LinearModel model = test::mdof2_model();  // c12 fixed at 0
  test::Mdof2Values damped;
  damped.c12 = 5;  // the helix damped: no parameter of the model can take it up
  const std::vector<DataSet> data = series(5, 3, damped);
  const MonitorResult r = monitor(model, data, {}, quick());
  REQUIRE(!r.changes.empty());
  CHECK(r.changes[0].index == 3);
  CHECK(r.changes[0].structural);
  CHECK(r.changes[0].misfit_ratio > 1.25);
  CHECK(r.changes.size() == 1);  // reported once, not again at set 4
}

TEST_CASE("monitor refuses a baseline that is too small or not followed by data", "[monitor]") {
  const test::LinearModel model = test::mdof2_model();
  const std::vector<DataSet> data = series(3, 3, {});
  MonitorOptions o = quick();
  CHECK_THROWS_AS(monitor(model, data, {}, o), FitError);  // 3 sets, baseline 3
  o.baseline = 1;
  CHECK_THROWS_AS(monitor(model, data, {}, o), FitError);
}
