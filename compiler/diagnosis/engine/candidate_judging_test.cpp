// The judgement of one candidate on hand-made fits: bounds pressed, parameters undetermined, the chain's
// descriptions, the variants that stand for a candidate and equivalent candidates.
#include "diagnosis/engine/candidate_judging.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace mbgen::diagnosis {
namespace {

ParameterEstimate estimate(const std::string& name, double value, double std_dev = 0.01) {
  ParameterEstimate p;
  p.name = name;
  p.prior = 1.0;
  p.value = value;
  p.std = std_dev;
  p.estimated = true;
  return p;
}

ParameterInfo bounded(const std::string& name, double lower, double upper) {
  ParameterInfo info;
  info.name = name;
  info.role = ParameterRole::Estimate;
  info.lower = lower;
  info.upper = upper;
  info.unit = "N/m";
  return info;
}

Extension chain_extension(const std::string& target, const std::string& parameter) {
  Extension e;
  e.id = std::string(kChainOperator) + ":" + target;
  e.operator_name = kChainOperator;
  e.target = target;
  e.new_parameters.push_back({parameter, "a channel's factor"});
  return e;
}

FitResult fit_with(const std::vector<ParameterEstimate>& parameters) {
  FitResult f;
  f.parameters = parameters;
  return f;
}

CandidateOutcome outcome(const std::string& id, const std::string& variant, double delta_bic, bool plausible = true,
                         std::size_t new_parameters = 1) {
  CandidateOutcome o;
  o.id = id;
  o.variant = variant;
  o.delta_bic = delta_bic;
  o.plausible = plausible;
  o.qualifies = plausible && delta_bic < -10;
  o.new_parameters.resize(new_parameters);
  return o;
}

}  // namespace

TEST_CASE("an estimate is pressed against a bound only when it stands there and the data pull beyond", "[judging]") {
  const ParameterInfo info = bounded("k", 0.0, 10.0);
  ParameterEstimate at_upper = estimate("k", 10.0);
  at_upper.pull_chi2 = 50;
  at_upper.toward = 1;
  CHECK(pressed_bound(at_upper, info) == "upper");
  ParameterEstimate slack = at_upper;
  slack.pull_chi2 = 5;  // the data barely pull: a drift to the bound, no misfit
  CHECK(pressed_bound(slack, info).empty());
  ParameterEstimate inside = at_upper;
  inside.value = 9.0;  // pulled up, but not at the bound
  CHECK(pressed_bound(inside, info).empty());
  ParameterEstimate near_zero = estimate("k", 1e-4);  // a bound at zero: within a thousandth of the prior
  near_zero.pull_chi2 = 50;
  near_zero.toward = -1;
  CHECK(pressed_bound(near_zero, info) == "lower");

  ModelInfo model;
  model.parameters = {info, bounded("c", 0.0, 5.0)};
  const std::vector<Discrepancy> found = bound_findings(fit_with({at_upper, estimate("c", 2.0)}), model);
  REQUIRE(found.size() == 1);
  CHECK(found[0].kind == "parameter_at_bound");
  CHECK(found[0].parameter == "k");
  CHECK(found[0].text.find("upper bound (10 N/m)") != std::string::npos);
}

TEST_CASE("a new parameter the data do not determine is held unless a bound holds it", "[judging]") {
  Extension ext;
  ext.new_parameters = {{"k_new", ""}, {"c_new", ""}, {"m_new", ""}};
  ParameterEstimate k = estimate("k_new", 1.0, 0.9);  // known to 90 %: undetermined
  ParameterEstimate c = estimate("c_new", 1.0);
  c.identifiable = false;                             // not identifiable: undetermined
  ParameterEstimate m = estimate("m_new", 1.0, 0.9);  // poorly known, but pressed against a bound: a doubt of its own
  m.pull_chi2 = 20;
  const std::vector<std::string> held = undetermined_new_parameters(ext, fit_with({k, c, m}));
  CHECK(held == std::vector<std::string>{"k_new", "c_new"});
}

TEST_CASE("a chain candidate's description names the channel, the factor and a unit mix-up", "[judging]") {
  const Extension output = chain_extension("gain:xs_rear", "g_xs_rear");
  CHECK(chain_description(output, fit_with({estimate("g_xs_rear", 0.8012, 0.0031)}), "x", false) ==
        "xs_rear reads 0.8012 +- 0.0031 times the structure's motion: its sensor's calibration");
  CHECK(chain_description(output, fit_with({estimate("g_xs_rear", -1.0, 0.001)}), "x", false) ==
        "xs_rear reads -1 +- 0.001 times the structure's motion: the sensor is mounted or wired reversed");
  CHECK(chain_description(output, fit_with({estimate("g_xs_rear", 1000.4, 0.5)}), "x", false) ==
        "xs_rear reads 1000 +- 0.5 times the structure's motion: a unit mix-up, millimetres read as metres");
  const Extension force = chain_extension("input:Fx", "g_Fx");
  CHECK(chain_description(force, fit_with({estimate("g_Fx", -1.0)}), "x", true) ==
        "the recorded Fx has the opposite sign of the force applied (a reaction force taken with the wrong sign); its "
        "size the data cannot tell from the structure's scale");
  Extension two = output;
  two.new_parameters.push_back({"second", ""});
  CHECK(chain_description(two, fit_with({estimate("g_xs_rear", 0.8)}), "as enumerated", false) == "as enumerated");
}

TEST_CASE("the best variant stands for its candidate, and those that fit as well are named with it", "[judging]") {
  std::vector<CandidateOutcome> outcomes = {
      outcome("untie:k", "rear", -40.005, true, 2), outcome("untie:k", "front", -40),  // a tie within 0.01: the simpler
      outcome("untie:k", "both", -60, false),                                          // lower, but implausible
      outcome("base", "", -30)};
  std::vector<ModelState> states(outcomes.size());
  states[0].text = "rear";
  states[1].text = "front";
  keep_best_variants(outcomes, states);
  REQUIRE(outcomes.size() == 2);
  CHECK(outcomes[0].variant == "front");
  CHECK(states[0].text == "front");
  CHECK(outcomes[0].variants_tried == 3);
  CHECK(outcomes[0].equivalent_variants == std::vector<std::string>{"rear"});
  CHECK(outcomes[0].description.find("rear instead fits exactly as well") != std::string::npos);
  CHECK(outcomes[1].id == "base");

  std::vector<CandidateOutcome> round = {outcome("a", "", -50), outcome("b", "", -50.001), outcome("c", "", -49)};
  CHECK(equivalents(round, 0) == std::vector<std::string>{"b"});
}

TEST_CASE("a candidate ranks against the current model by BIC and validation", "[judging]") {
  DiagnoseOptions options;  // min delta BIC -10, validation gain 1 %
  ModelState base;
  base.fit.bic = 100;
  base.validation_nrmse = 0.2;
  CandidateOutcome o;
  o.plausible = true;
  o.fit.bic = 80;
  o.validation_nrmse = 0.19;
  rank_against(base, options, o);
  CHECK(o.delta_bic == Approx(-20));
  CHECK(o.qualifies);
  o.validation_nrmse = 0.199;  // less than 1 % better on the held-back data
  rank_against(base, options, o);
  CHECK_FALSE(o.qualifies);
}

}  // namespace mbgen::diagnosis
