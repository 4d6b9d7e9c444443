// The method table (mbgen/methods/method_table.hpp): its entries are complete and consistent, the data checks say
// what the methods themselves say, and each entry runs its own method. Data from mdof2's closed forms
// (test_support), independent of the code under test.
#include "mbgen_test/estimation.hpp"

#include "mbgen/methods/method_table.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <string>

using namespace mbgen;

namespace {

FrfData frf_data() {
  std::mt19937 rng(1);
  FrfData d = test::mdof2_frf_data(test::Mdof2Values{}, Eigen::VectorXd::LinSpaced(391, 10, 400), 0.0, rng);
  d.file = "frf.csv";
  return d;
}

TimeRecord time_record() {
  std::mt19937 rng(1);
  TimeRecord r = test::mdof2_time_record(test::Mdof2Values{}, 2048, 1.0 / 1024, 0.0, rng);
  r.file = "rec.csv";
  return r;
}

// The message of the FitError that `method`'s run throws on `data`, "" when it throws none.
std::string refusal_of_run(const std::string& method, const DataSet& data) {
  const test::LinearModel model = test::mdof2_model(test::Mdof2Values{}, true);
  FitOptions fit;
  fit.starts = 1;
  const MethodOptions options;
  try {
    find_method(method)->run({model, {data}, fit, options});
  } catch (const FitError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("method table: one entry per name, each complete", "[method_table]") {
  const std::vector<std::string> names = method_names();
  CHECK(names.front() == "auto");  // output error, the default, is first
  CHECK(std::set<std::string>(names.begin(), names.end()).size() == names.size());
  for (const MethodDescriptor& m : method_table()) {
    INFO(m.name);
    CHECK(find_method(m.name) == &m);
    CHECK(m.run != nullptr);
    CHECK((m.takes_frf || m.takes_records));
    // A method that refuses a kind of data says what it needs instead.
    if (!m.takes_frf || !m.takes_records) CHECK_FALSE(m.needs.empty());
    for (const MethodPrecondition& p : m.preconditions) {
      CHECK_FALSE(p.needs.empty());
      CHECK_FALSE(p.refusal.empty());
      REQUIRE_FALSE(p.instead.empty());
      for (const std::string& other : p.instead) CHECK(find_method(other) != nullptr);
    }
  }
  CHECK(find_method("least-squares") == nullptr);
}

TEST_CASE("method table: options typed, their defaults among their choices", "[method_table]") {
  MethodOptions defaults;
  std::set<std::string> flags;
  for (const MethodDescriptor& m : method_table())
    for (const MethodOption& o : m.options) {
      INFO(o.flag);
      CHECK(flags.insert(o.flag).second);
      CHECK(find_method_option(o.flag) == &o);
      CHECK_FALSE(o.help.empty());
      if (o.kind == MethodOption::Kind::Choice) {
        REQUIRE(o.text != nullptr);
        CHECK(o.number == nullptr);
        const std::string value = o.text(defaults);
        CHECK(std::find(o.choices.begin(), o.choices.end(), value) != o.choices.end());
      } else {
        REQUIRE(o.number != nullptr);
        CHECK(o.text == nullptr);
        CHECK(o.number(defaults) >= 0);
      }
    }
  // The accessors reach the members the methods read.
  find_method_option("--two-step-model")->text(defaults) = "arx";
  CHECK(defaults.two_step.model == "arx");
  find_method_option("--ekf-drift")->number(defaults) = 0.25;
  CHECK(defaults.ekf.drift == 0.25);
}

TEST_CASE("method table: data refusals name the file, the need and the methods that take the data",
          "[method_table]") {
  const DataSet frf(frf_data());
  const DataSet record(time_record());
  CHECK(data_refusal(*find_method("auto"), frf).empty());
  CHECK(data_refusal(*find_method("auto"), record).empty());
  CHECK(data_refusal(*find_method("two-step"), record).empty());
  CHECK(data_refusal(*find_method("frf-output-error"), record) ==
        "rec.csv: error: --method frf-output-error needs FRF data, but this is a time record\n"
        "note: methods that take time records: auto, time-output-error, direct, two-step, hybrid, ekf, "
        "arx-two-stage or eiv");
  CHECK(data_refusal(*find_method("modal"), record).rfind(
            "rec.csv: error: --method modal needs FRFs (it identifies modes from them), but this is a time record\n",
            0) == 0);
  CHECK(data_refusal(*find_method("ekf"), frf) ==
        "frf.csv: error: --method ekf needs time records (sampled inputs and outputs), but this file holds FRFs\n"
        "note: methods that take FRFs: auto, frf-output-error, direct, two-step, hybrid or modal");
}

TEST_CASE("method table: the refusals agree with the methods' own", "[method_table]") {
  // Each method that refuses a kind of data refuses it in its run with the table's words (the first line of the
  // table's refusal), so the CLI's early check changes no message.
  for (const MethodDescriptor& m : method_table()) {
    if (m.output_error) continue;  // mbgen::fit takes both kinds; the named domains are the table's alone
    for (const DataSet& d : {DataSet(frf_data()), DataSet(time_record())}) {
      const std::string table = data_refusal(m, d);
      if (table.empty()) continue;
      INFO(m.name << " on " << d.file());
      CHECK(refusal_of_run(m.name, d) == table.substr(0, table.find('\n')));
    }
  }
}

TEST_CASE("method table: each entry runs its own method", "[method_table]") {
  const test::LinearModel model = test::mdof2_model(test::Mdof2Values{}, true);
  const std::vector<DataSet> data{DataSet(frf_data())};
  FitOptions fit;
  fit.starts = 1;
  const MethodOptions options;
  CHECK(find_method("direct")->run({model, data, fit, options}).method == "direct");
  CHECK(find_method("hybrid")->run({model, data, fit, options}).method == "hybrid");
  CHECK(find_method("frf-output-error")->run({model, data, fit, options}).method == "frf-output-error");
}

TEST_CASE("method table: a refusal that shows a precondition gets a note naming the methods that do without",
          "[method_table]") {
  const MethodDescriptor& arx = *find_method("arx-two-stage");
  CHECK(preconditions_note(arx, "fit: --method arx-two-stage needs the mass matrix known (C = -M F1, ...): the "
                                "estimated parameters m1, m2 enter M") ==
        "note: --method auto or ekf does without the mass matrix known (no estimated parameter in M)");
  CHECK(preconditions_note(arx, "fit: --method arx-two-stage: lags must be 2 to 8").empty());
  CHECK(preconditions_note(*find_method("auto"), "anything").empty());
  // Each precondition's refusal is a text its method says (checked on a refusal the run gives).
  const std::string two_step = refusal_of_run("two-step", DataSet([] {
                                                TimeRecord r = time_record();
                                                r.t.conservativeResize(41);
                                                for (Signal& s : r.signals) s.values.conservativeResize(41);
                                                return r;
                                              }()));
  INFO(two_step);
  CHECK(preconditions_note(*find_method("two-step"), two_step) ==
        "note: --method auto does without at least 20 samples of a record per coefficient of the model's order");
}
