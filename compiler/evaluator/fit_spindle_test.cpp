// Output-error fits of the spindle (examples/spindle/spindle.mdl) on the committed example FRFs
// examples/spindle/data/frf_Fx.csv (made by scripts/truthgen, an independent numpy assembly of the model; truth
// values in frf_Fx.truth.json; 40 dB SNR).
//
// The test lives beside the evaluator because it needs the model from the .mdl: the runtime's own tests cannot
// link the compiler, and the in-process evaluator is what `mbgen fit` uses.
#include "mbgen_test/example_data.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"

#include "mbgen/data/data_set.hpp"
#include "mbgen/estimation/fit.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <set>

using namespace mbgen;

namespace {


std::unique_ptr<Model> spindle_model() {
  return evaluator::make_evaluator(frontend::parse_file(test::example_model_path("spindle")));
}

DataSet spindle_data() { return test::example_data("examples/spindle/data/frf_Fx.csv"); }

std::map<std::string, double> truth_parameters() {
  std::ifstream in(test::source_path("examples/spindle/data/frf_Fx.truth.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  std::map<std::string, double> out;
  for (const auto& [name, value] : j.at("parameters").items()) out[name] = value.get<double>();
  return out;
}

// The x-direction force and outputs excite the x / ry / rz block (spindle x, ry; housing x, ry, rz). The springs
// acting there: the x bearings, and the mounts in all three directions (x directly; y through the housing's rz,
// the mounts sitting at x = +-0.048; z through its ry). The y / z bearings act only in the other block.
const std::set<std::string> kXPlane = {"k_fx", "k_rx", "k_hbx", "k_hby", "k_hbz",
                                       "c_fx", "c_rx", "c_hbx", "c_hby", "c_hbz"};
const std::set<std::string> kOtherPlane = {"k_fy", "k_ry", "k_fz", "c_fy", "c_ry", "c_fz"};

}  // namespace

TEST_CASE("slow: Spindle FRF data: bearing and mount stiffnesses within 2 % of the truth at 40 dB SNR",
          "[fit][frf][spindle][slow]") {
  const auto model = spindle_model();
  const std::map<std::string, double> truth = truth_parameters();
  // From the model file's defaults (the nominal values; the truth is 3-10 % off), as `mbgen fit` does.
  const FitResult r = fit(*model, {spindle_data()}, FitOptions{});
  INFO("nrmse " << r.nrmse << ", cost " << r.cost << ", best start " << r.best_start);
  REQUIRE(r.parameters.size() == kXPlane.size() + kOtherPlane.size());
  for (const ParameterEstimate& e : r.parameters) {
    const double t = truth.at(e.name);
    INFO(e.name << " = " << e.value << " +- " << e.std << ", truth " << t << ", prior " << e.prior);
    if (kOtherPlane.count(e.name)) {
      CHECK_FALSE(e.identifiable);
      CHECK(e.value == e.prior);
      continue;
    }
    REQUIRE(kXPlane.count(e.name));
    CHECK(e.identifiable);
    if (e.name[0] == 'k') CHECK(std::abs(e.value - t) < 0.02 * t);
  }
  // 40 dB SNR: the noise is 1 % of each channel's RMS |H|.
  CHECK(r.nrmse < 0.013);
}

TEST_CASE("slow: spindle: from 20 random starts spread over a factor of 3 around the truth, every run reaches the "
          "global optimum",
          "[fit][frf][spindle][global][slow]") {
  const auto model = spindle_model();
  const std::map<std::string, double> truth = truth_parameters();
  const DataSet data = spindle_data();
  // Reference optimum: a single local fit started at the truth.
  FitOptions at_truth;
  at_truth.starts = 1;
  for (const auto& name : kXPlane) at_truth.values[name] = truth.at(name);
  for (const auto& name : kOtherPlane) at_truth.values[name] = truth.at(name);
  const FitResult reference = fit(*model, {data}, at_truth);
  std::mt19937 prior_rng(2024);
  std::uniform_real_distribution<double> exponent(-1, 1);
  for (int run = 0; run < 20; ++run) {
    FitOptions o;
    o.seed = static_cast<unsigned>(run + 1);
    o.starts = 8;
    // Every estimable parameter's prior drawn; the other plane's stay at their (random) priors, unidentifiable.
    for (const auto* names : {&kXPlane, &kOtherPlane})
      for (const auto& name : *names) o.values[name] = truth.at(name) * std::pow(3.0, exponent(prior_rng));
    const FitResult r = fit(*model, {data}, o);
    INFO("run " << run << ": cost " << r.cost << " vs reference " << reference.cost << ", best start " << r.best_start);
    CHECK(r.cost == Approx(reference.cost).epsilon(1e-6));
    for (std::size_t i = 0; i < r.parameters.size(); ++i)
      if (r.parameters[i].identifiable)
        CHECK(r.parameters[i].value == Approx(reference.parameters[i].value).epsilon(1e-4));
  }
}
