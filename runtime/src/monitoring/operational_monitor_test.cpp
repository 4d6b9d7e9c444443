// Monitoring in operation on features made by hand: the F quantile and the T^2 limit against tables, the stated
// false-alarm rate on simulated series (regression and principal components), a step found with the mode that
// moved, tracking by MAC, and the `# condition` reader's errors.
#include "mbgen/monitoring/operational_monitor.hpp"
#include "mbgen/monitoring/operating_conditions.hpp"

#include "mbgen/data/data_error.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <random>

using namespace mbgen;

namespace {

OperationalMode mode(double f, Eigen::VectorXcd shape) {
  OperationalMode m;
  m.f_hz = f;
  m.zeta = 0.01;
  m.shape = shape.normalized();
  return m;
}

const Eigen::VectorXcd kShapeA = (Eigen::VectorXcd(2) << 1.0, 0.6).finished();
const Eigen::VectorXcd kShapeB = (Eigen::VectorXcd(2) << -0.6, 1.0).finished();

// A series of two modes whose frequencies fall 0.1 % per degree with a temperature that drifts beyond the baseline's
// range, plus independent scatter (0.02 % relative); from set `step` on the second mode 1 % down.
std::vector<OperationalSet> series(std::mt19937_64& rng, int n, int step, bool drift = true) {
  std::normal_distribution<double> normal;
  std::vector<OperationalSet> sets;
  for (int i = 0; i < n; ++i) {
    const double t = 20 + 4 * std::sin(2 * M_PI * i / 12) + (drift ? 0.6 * i : 0) + 0.3 * normal(rng);
    const double factor = 1 - 0.001 * (t - 20);
    OperationalSet s;
    s.file = "set" + std::to_string(i);
    s.conditions = {t};
    const double f2 = 150 * factor * (i >= step ? 0.99 : 1.0);
    s.modes = {mode(90 * factor * (1 + 2e-4 * normal(rng)), kShapeA), mode(f2 * (1 + 2e-4 * normal(rng)), kShapeB)};
    sets.push_back(std::move(s));
  }
  return sets;
}

}  // namespace

TEST_CASE("F quantiles and the T^2 limit match tables", "[monitor]") {
  // F_0.99(2, 9) = 8.0215, F_0.95(1, 10) = 4.9646, F_0.99(3, 20) = 4.9382 (Abramowitz & Stegun Table 26.9).
  CHECK(f_distribution_quantile(0.99, 2, 9) == Approx(8.0215).epsilon(1e-4));
  CHECK(f_distribution_quantile(0.95, 1, 10) == Approx(4.9646).epsilon(1e-4));
  CHECK(f_distribution_quantile(0.99, 3, 20) == Approx(4.9382).epsilon(1e-4));
  CHECK(f_distribution_cdf(f_distribution_quantile(0.9, 4, 7), 4, 7) == Approx(0.9).epsilon(1e-10));
  CHECK(hotelling_limit(2, 10, 0.01) == Approx(20.0 / 9 * 8.0215).epsilon(1e-4));
  CHECK_THROWS_AS(hotelling_limit(3, 2, 0.01), std::invalid_argument);
}

TEST_CASE("the T^2 chart keeps its stated false-alarm rate on simulated drifting series", "[monitor]") {
  // 600 series of 20 sets (12 baseline), the last one tested, its temperature well beyond the baseline's (the
  // regression extrapolates; the leverage widens the limit), at alpha = 0.05: 30 alarms expected, binomial sd 5.3.
  std::mt19937_64 rng(11);
  OperationalMonitorOptions options;
  options.baseline = 12;
  options.false_alarm = 0.05;
  int regression = 0, components = 0, raw = 0;
  const int runs = 600;
  for (int r = 0; r < runs; ++r) {
    const std::vector<OperationalSet> sets = series(rng, 20, 1000);
    regression += monitor_operational(sets, {"temperature"}, options).series.back().alarm;
    std::vector<OperationalSet> unmeasured = sets;  // the temperature not given: principal components
    for (OperationalSet& s : unmeasured) s.conditions.clear();
    components += monitor_operational(unmeasured, {}, options).series.back().alarm;
    OperationalMonitorOptions plain = options;
    plain.compensate = false;
    raw += monitor_operational(sets, {"temperature"}, plain).series.back().alarm;
  }
  std::printf("false alarms in %d tested sets at 5 %%: regression %d, principal components %d, uncompensated %d\n",
              runs, regression, components, raw);
  CHECK(regression >= 14);  // 30 +- 3 sd
  CHECK(regression <= 46);
  CHECK(components <= 46);
  CHECK(raw > 300);  // the drift beyond the baseline's range alarms without compensation
}

TEST_CASE("a step is found at its set, naming the mode that moved, over a drift", "[monitor]") {
  std::mt19937_64 rng(5);
  OperationalMonitorOptions options;
  options.baseline = 12;
  const OperationalMonitorResult r = monitor_operational(series(rng, 24, 18), {"temperature"}, options);
  REQUIRE(r.changes.size() == 1);
  CHECK(r.changes[0].index == 18);
  CHECK(r.changes[0].last == 23);
  CHECK(r.changes[0].modes == std::vector<int>{1});
  CHECK(r.changes[0].shift_percent[1] == Approx(-1).margin(0.1));
  // The regression learnt the drift: -0.1 % per degree of 90 and 150 Hz.
  CHECK(r.effects[0][0] == Approx(-0.09).epsilon(0.1));
  CHECK(r.effects[1][0] == Approx(-0.15).epsilon(0.1));
  for (int i = 12; i < 18; ++i) CHECK_FALSE(r.series[static_cast<std::size_t>(i)].alarm);
}

TEST_CASE("modes are tracked by MAC, not by their order", "[monitor]") {
  std::mt19937_64 rng(3);
  std::vector<OperationalSet> sets = series(rng, 14, 1000, false);
  // A spurious mode with the first mode's frequency but another shape, listed first in one set: not tracked.
  sets[13].modes.insert(sets[13].modes.begin(), mode(90.01, (Eigen::VectorXcd(2) << 0.0, 1.0).finished()));
  OperationalMonitorOptions options;
  options.baseline = 12;
  const OperationalMonitorResult r = monitor_operational(sets, {"temperature"}, options);
  CHECK(r.series[13].identified == 3);
  CHECK(r.series[13].f_hz[0] == Approx(sets[13].modes[1].f_hz));
  CHECK(r.series[13].mac[0] == Approx(1.0));
  // A mode lost in a later set: that set is not tested.
  sets[13].modes.erase(sets[13].modes.begin() + 2);
  const OperationalMonitorResult lost = monitor_operational(sets, {"temperature"}, options);
  CHECK(std::isnan(lost.series[13].t2));
  CHECK_FALSE(lost.series[13].alarm);
  // Too small a baseline for two modes and one condition (it needs 4 sets).
  options.baseline = 3;
  CHECK_THROWS_WITH(monitor_operational(sets, {"temperature"}, options), Catch::Contains("at least 4"));
}

namespace {

std::string condition_error(const std::string& text) {
  const std::string path = "operational_condition_test.csv";
  std::ofstream(path) << text;
  try {
    read_operating_conditions(path);
  } catch (const DataError& e) {
    std::remove(path.c_str());
    return e.what();
  }
  std::remove(path.c_str());
  return "";
}

}  // namespace

TEST_CASE("`# condition` lines: values, plain comments, errors with line and column", "[monitor]") {
  const std::string path = "operational_condition_ok.csv";
  std::ofstream(path) << "# conditioned air (a comment)\n#condition speed=300\n# condition  temperature = 1\n"
                         "# condition temperature=-2.5e1\n# time=2026-01-01\nt,a,b\n0,1,2\n# condition x=1\n";
  CHECK_THROWS_WITH(read_operating_conditions(path), Catch::Contains(":3:14: error: bad '# condition' line: "
                                                                     "'temperature ' is not a name"));
  std::ofstream(path) << "# conditioned air\n#condition speed=300\n# condition temperature=-2.5e1\nt,a\n0,1\n"
                         "# condition x=1\n";
  const std::vector<ConditionValue> c = read_operating_conditions(path);
  std::remove(path.c_str());
  REQUIRE(c.size() == 2);
  CHECK(c[0].name == "speed");
  CHECK(c[0].value == 300);
  CHECK(c[0].line == 2);
  CHECK(c[1].value == -25);
  CHECK_THAT(condition_error("# condition\nt\n"), Catch::Contains(":1:12: error: bad '# condition' line: expected NAME=VALUE"));
  CHECK_THAT(condition_error("# condition t=inf\nt\n"), Catch::Contains(":1:15: error: bad '# condition' line: 'inf'"));
  CHECK_THAT(condition_error("# condition t=0x10\nt\n"), Catch::Contains("'0x10' is not a finite decimal number"));
  CHECK_THAT(condition_error("# condition t=1\n# condition t=2\nt\n"),
             Catch::Contains(":2:13: error: a second '# condition t=' line (the first is on line 1)"));
  // Every set must give the same variables.
  const ConditionTable table = condition_table({"a", "b"}, {{{"t", 1, 1}}, {{"t", 2, 1}}});
  CHECK(table.values[1][0] == 2);
  CHECK_THROWS_WITH(condition_table({"a", "b"}, {{{"t", 1, 1}}, {}}), Catch::Contains("b: error: no '# condition t='"));
  CHECK_THROWS_WITH(condition_table({"a", "b"}, {{}, {{"s", 1, 4}}}), Catch::Contains("b:4: error: '# condition s='"));
}
