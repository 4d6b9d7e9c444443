// fit_modal on mdof2 FRFs made by the independent truth generator (scripts/truthgen: numpy, its own model assembly),
// truth drawn at random (--draw: every estimable parameter 3-10 % off the model's values), 40 dB SNR. The model is
// test_support's hand-written mdof2 with the .mdl's values and bounds.
#include "mbgen_test/estimation.hpp"
#include "mbgen_test/truthgen.hpp"

#include "mbgen/methods/modal_fit.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

using namespace mbgen;

namespace {

// truthgen's mdof2 `nominal` case at 40 dB, FRFs, truth draw `draw`, noise seed `seed`, extra arguments `extra`.
test::TruthgenData generate(int draw, int seed, const std::string& extra = "", const std::string& tag = "") {
  return test::truthgen_data("--example mdof2 --case nominal --snr-db 40 --kind frf --draw " + std::to_string(draw) +
                                 " --seed " + std::to_string(seed) + " " + extra,
                             "methods_modal", "frf_draw" + std::to_string(draw) + "_seed" + std::to_string(seed) + tag);
}

// Every parameter within `relative` of the truth.
void check_truth(const FitResult& r, const std::map<std::string, double>& truth, double relative) {
  CHECK(r.method == "modal");
  CHECK(r.converged);
  REQUIRE(r.parameters.size() == 7);
  for (const ParameterEstimate& e : r.parameters) {
    const double t = truth.at(e.name);
    INFO(e.name << " = " << e.value << ", truth " << t << " (" << (e.value / t - 1) * 100 << " %)");
    CHECK(e.identifiable);
    CHECK(std::abs(e.value / t - 1) < relative);
  }
}

// The paper's test for the global optimum, per subproblem of the last sweep: every repetition from the seeded starts
// (a factor up to 3 off the current values) agrees with the best (every parameter within 1e-3) and they spread by
// less than `relative_std`. (mdof2 has no local optimum within that range from the model's values; the spindle has,
// tests/cli/methods_modal.) With `local_optima_allowed`, the paper's weaker form: at least half the repetitions agree
// with the best, and those that stop elsewhere cost over 100 times more (local optima, reported as such).
void check_spread(const FitResult& r, double relative_std, bool local_optima_allowed = false) {
  const nlohmann::json d = nlohmann::json::parse(r.method_details.at("modal"));
  const nlohmann::json& last = d.at("repetitions").at("last_sweep");
  REQUIRE(last.size() == 2);  // mdof2: two modes, a subproblem each
  int parameters = 0;
  for (const auto& sub : last) {
    INFO(sub.dump());
    if (local_optima_allowed) {
      CHECK(2 * sub.at("agreeing").get<int>() >= sub.at("repetitions").get<int>());
      for (const auto& c : sub.at("local_optimum_costs")) CHECK(c.get<double>() > 100 * sub.at("best_cost").get<double>());
    } else {
      CHECK(sub.at("agreeing").get<int>() == sub.at("repetitions").get<int>());
      CHECK(sub.at("local_optimum_costs").empty());
    }
    for (const auto& [name, s] : sub.at("parameters").items()) {
      CHECK(s.at(local_optima_allowed ? "agreeing_relative_std" : "relative_std").get<double>() < relative_std);
      ++parameters;
    }
  }
  CHECK(parameters == 5);
}

}  // namespace

// Measured: largest error 0.11 % (draw 1), 0.14 % (draw 4, k22), 0.32 % (draw 2 below, k12); asserted 0.5 %.
TEST_CASE("truthgen mdof2 FRF draws 1 and 4: modal reaches the truth", "[modal]") {
  for (auto [draw, seed] : {std::pair{1, 3}, std::pair{4, 14}}) {
    INFO("draw " << draw);
    const test::TruthgenData g = generate(draw, seed);
    const test::LinearModel model = test::mdof2_model({}, true);
    FitOptions o;
    o.starts = 8;
    const FitResult r = fit_modal(model, {g.data}, o);
    check_truth(r, g.truth, 0.005);
    check_spread(r, 1e-6);
    const nlohmann::json d = nlohmann::json::parse(r.method_details.at("modal"));
    REQUIRE(d.at("reference_modes").size() == 2);
    for (const auto& a : d.at("agreement")) {
      CHECK(a.at("mac").get<double>() > 0.9999);
      CHECK(std::abs(a.at("nfd").get<double>()) < 1e-4);
      CHECK(std::abs(a.at("ndd").get<double>()) < 1e-6);  // two modes, two damping parameters: solved exactly
    }
  }
}

// Poor starts: the priors a factor 2-3 off the model's values, in different directions; both reach the same optimum as
// from the model's values (and the truth). Two drawn truths. On draw 2 every repetition of every subproblem agrees;
// on draw 3 from the first poor prior, 3 of the 8 repetitions of the mass-1 subproblem stop at a local optimum
// (k22 driven off by orders of magnitude, cost ~1700 times the best), which the spread reports and the best
// repetition avoids: the paper's test doing its work, so there the weaker form of check_spread.
TEST_CASE("truthgen mdof2 FRF draws 2 and 3: modal from poor starts reaches one optimum", "[modal]") {
  const test::LinearModel model = test::mdof2_model({}, true);
  for (auto [draw, seed] : {std::pair{2, 5}, std::pair{3, 7}}) {
    INFO("draw " << draw);
    const test::TruthgenData g = generate(draw, seed);
    FitOptions o;
    o.starts = 8;
    const FitResult reference = fit_modal(model, {g.data}, o);
    check_truth(reference, g.truth, 0.005);
    const std::vector<std::map<std::string, double>> poor = {{{"m1", 2 * 1.39},
                                                              {"m2", 1.09 / 2},
                                                              {"k11", 1.38e6 / 3},
                                                              {"k22", 0.24e6 * 2},
                                                              {"k12", 0.12e6 * 3},
                                                              {"c11", 13.42 * 3},
                                                              {"c22", 0.47 / 3}},
                                                             {{"m1", 1.39 / 2},
                                                              {"m2", 1.09 * 2},
                                                              {"k11", 1.38e6 * 2},
                                                              {"k22", 0.24e6 / 3},
                                                              {"k12", 0.12e6 / 2},
                                                              {"c11", 13.42 / 3},
                                                              {"c22", 0.47 * 3}}};
    for (std::size_t k = 0; k < poor.size(); ++k) {
      INFO("poor start " << k);
      o.values = poor[k];
      o.seed = 11 + k;
      const FitResult r = fit_modal(model, {g.data}, o);
      check_spread(r, 1e-6, draw == 3);
      for (std::size_t i = 0; i < r.parameters.size(); ++i) {
        INFO(r.parameters[i].name << ": " << r.parameters[i].value << " vs " << reference.parameters[i].value);
        CHECK(std::abs(r.parameters[i].value / reference.parameters[i].value - 1) < 1e-6);
      }
    }
  }
}

TEST_CASE("modal refuses time records and too few modes", "[modal]") {
  const test::LinearModel model = test::mdof2_model({}, true);
  const test::TruthgenData time =
      test::truthgen_data("--example mdof2 --case nominal --kind time --duration 0.25 --seed 2", "methods_modal", "time");
  CHECK_THROWS_WITH(fit_modal(model, {time.data}), Catch::Contains("needs FRFs") && Catch::Contains("time record"));
  // A band up to 120 Hz holds the first mode (about 90 Hz) alone: 3 numbers for 5 mass/stiffness parameters.
  const test::TruthgenData low = generate(1, 3, "--f-max 120", "_low");
  CHECK_THROWS_WITH(fit_modal(model, {low.data}),
                    Catch::Contains("show 1 mode(s)") && Catch::Contains("fewer than the 5 mass/stiffness"));
  // The driving point alone: both modes, but per mode only frequency and scale, 4 numbers for 5 parameters.
  test::TruthgenData both = generate(1, 3);
  FrfData one = std::get<FrfData>(both.data.content);
  one.channels.erase(one.channels.begin() + 1);
  REQUIRE(one.channels.front().output == "d1");
  CHECK_THROWS_WITH(fit_modal(model, {DataSet(one)}),
                    Catch::Contains("show 2 mode(s)") && Catch::Contains("1 channel(s), which give 4 numbers"));
}

// Several configurations (Ellinger & Zaeh identify over several machine positions; in mbgen a configuration is a
// data set's `# set` values). mdof2's driving point d1/F1 alone, as built (A) and with a helix of known stiffness
// fitted instead (B: `# set k12=240000`). A alone gives 4 numbers (two frequencies, two scales) for the 5
// mass/stiffness parameters: refused. B alone determines m1, m2, k11, k22, but not k12, which it sets: kept at the
// prior, not identifiable. Both together determine all seven, k12 from A's modes once B has fixed the rest.
// Measured on draws 1-2: B alone m1, m2, k11, k22 within 0.09 %; both every parameter within 0.17 %.
TEST_CASE("truthgen mdof2 driving point in two configurations: k12 from both, not from either", "[modal][configurations]") {
  const test::LinearModel model = test::mdof2_model({}, true);
  auto driving_point = [](const test::TruthgenData& g) {
    FrfData f = std::get<FrfData>(g.data.content);
    f.channels.erase(std::remove_if(f.channels.begin(), f.channels.end(),
                                    [](const FrfChannel& c) { return c.output != "d1"; }),
                     f.channels.end());
    REQUIRE(f.channels.size() == 1);
    return DataSet(f);
  };
  for (auto [draw, seed] : {std::pair{1, 41}, std::pair{2, 42}}) {
    INFO("draw " << draw);
    const test::TruthgenData a = generate(draw, seed, "", "_config_a");
    const test::TruthgenData b = generate(draw, seed + 100, "--set k12=240000", "_config_b");
    REQUIRE(b.truth.at("k12") == 240000);
    const DataSet A = driving_point(a), B = driving_point(b);
    REQUIRE(B.set().count("k12"));
    FitOptions o;
    o.starts = 8;
    CHECK_THROWS_WITH(fit_modal(model, {A}, o),
                      Catch::Contains("which give 4 numbers") && Catch::Contains("fewer than the 5 mass/stiffness"));

    const FitResult alone = fit_modal(model, {B}, o);
    const nlohmann::json da = nlohmann::json::parse(alone.method_details.at("modal"));
    CHECK(da.at("partition").at("set_in_every_configuration") == nlohmann::json::array({"k12"}));
    for (const ParameterEstimate& e : alone.parameters) {
      const double t = a.truth.at(e.name);
      INFO("B alone: " << e.name << " = " << e.value << ", truth " << t);
      if (e.name == "k12") {
        CHECK_FALSE(e.identifiable);
        CHECK(e.value == e.prior);
      } else if (e.name[0] != 'c') {
        CHECK(e.identifiable);
        CHECK(std::abs(e.value / t - 1) < 0.005);
      }
    }

    const FitResult both = fit_modal(model, {A, B}, o);
    const nlohmann::json d = nlohmann::json::parse(both.method_details.at("modal"));
    REQUIRE(d.at("configurations").size() == 2);
    CHECK(d.at("configurations")[1].at("set").at("k12") == 240000);
    CHECK(d.at("reference_modes").size() == 4);
    CHECK(d.at("partition").at("set_in_every_configuration").empty());
    CHECK(both.converged);
    for (const ParameterEstimate& e : both.parameters) {
      const double t = a.truth.at(e.name);
      INFO("both: " << e.name << " = " << e.value << ", truth " << t << " (" << (e.value / t - 1) * 100 << " %)");
      CHECK(e.identifiable);
      CHECK(std::abs(e.value / t - 1) < 0.005);
    }
    for (const auto& ag : d.at("agreement")) {
      CHECK(ag.at("mac").get<double>() > 0.9999);
      CHECK(std::abs(ag.at("nfd").get<double>()) < 1e-4);
    }
    // The paper's test: most repetitions of every subproblem reach the best optimum; those that stop elsewhere
    // (draw 1: one of eight in two subproblems) cost far more (local optima).
    for (const auto& sub : d.at("repetitions").at("last_sweep")) {
      INFO(sub.dump());
      CHECK(2 * sub.at("agreeing").get<int>() > sub.at("repetitions").get<int>());
      for (const auto& c : sub.at("local_optimum_costs")) CHECK(c.get<double>() > 1e3 * sub.at("best_cost").get<double>());
    }
    // The partition spans both configurations: some subproblem's objectives include configuration B's modes.
    bool uses_b = false;
    for (const auto& sub : d.at("partition").at("subproblems"))
      for (const auto& c : sub.at("objective_configurations")) uses_b = uses_b || c.get<int>() == 1;
    CHECK(uses_b);
  }
}
