// Frequency-domain output-error fits of mdof2 on FRFs from the closed-form transfer functions of
// docs/reference-models.md (test_support.hpp), with noise at 40 dB SNR.
#include "mbgen_test/estimation.hpp"

#include "mbgen/estimation/fit.hpp"
#include "mbgen/estimation/parameterization.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <set>

using namespace mbgen;

namespace {

Eigen::VectorXd truth_vector(const test::Mdof2Values& v) {
  Eigen::VectorXd p(8);
  p << v.m1, v.m2, v.k11, v.k22, v.k12, v.c11, v.c22, v.c12;
  return p;
}

Eigen::VectorXd frequencies() { return Eigen::VectorXd::LinSpaced(2241, 20, 300); }  // 0.125 Hz steps

}  // namespace

TEST_CASE("FRF fit of mdof2 at 40 dB SNR recovers the seven parameters within 3 std", "[fit][frf]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(3);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  test::Mdof2Values prior = truth;
  prior.m1 *= 0.9; prior.m2 *= 1.1; prior.k11 *= 0.9; prior.k22 *= 1.1; prior.k12 *= 0.9;
  prior.c11 *= 1.3; prior.c22 *= 0.7;
  const test::LinearModel model = test::mdof2_model(prior);
  FitOptions options;
  options.starts = 4;
  const FitResult r = fit(model, {DataSet(data)}, options);
  const Eigen::VectorXd p = truth_vector(truth);
  for (int i = 0; i < 7; ++i) {
    const ParameterEstimate& e = r.parameters[static_cast<std::size_t>(i)];
    INFO(e.name << " = " << e.value << " +- " << e.std << ", truth " << p[i]);
    CHECK(e.identifiable);
    CHECK(std::abs(e.value - p[i]) < 3 * e.std);
  }
  CHECK(r.method == "frf-output-error");
  // Uniform weights at 1 % of the RMS per component pair: the weighted RSS per residual is about 1e-4 / (2 * 1e-6)...
  // i.e. each weighted residual has unit variance, so the residual variance estimate is close to 1e-4 / 1 ... checked via nrmse.
  CHECK(r.nrmse == Approx(0.01).epsilon(0.2));
}

TEST_CASE("slow: global search from 20 random priors within a factor 3 of the truth always finds the optimum",
          "[fit][frf][global][slow]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(5);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  // Reference optimum: a fit started at the truth.
  const FitResult reference = [&] {
    FitOptions o;
    o.starts = 1;
    return fit(test::mdof2_model(truth), {DataSet(data)}, o);
  }();
  std::mt19937 prior_rng(99);
  std::uniform_real_distribution<double> exponent(-1, 1);
  for (int run = 0; run < 20; ++run) {
    test::Mdof2Values prior = truth;
    for (double* x : {&prior.m1, &prior.m2, &prior.k11, &prior.k22, &prior.k12, &prior.c11, &prior.c22})
      *x *= std::pow(3.0, exponent(prior_rng));
    FitOptions o;
    o.seed = static_cast<unsigned>(run + 1);
    o.starts = 8;
    const FitResult r = fit(test::mdof2_model(prior), {DataSet(data)}, o);
    INFO("run " << run << ": cost " << r.cost << " vs reference " << reference.cost << ", best start " << r.best_start);
    CHECK(r.cost == Approx(reference.cost).epsilon(1e-6));
    for (int i = 0; i < 7; ++i)
      CHECK(r.parameters[static_cast<std::size_t>(i)].value ==
            Approx(reference.parameters[static_cast<std::size_t>(i)].value).epsilon(1e-4));
  }
}

TEST_CASE("slow: the multi-start result does not depend on the number of threads, nor on sharing a budget of cores",
          "[fit][frf][global][slow]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(8);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  test::Mdof2Values prior = truth;
  prior.k11 *= 2;
  prior.m2 *= 0.5;
  FitOptions one;
  one.starts = 6;
  one.threads = 1;
  FitOptions two = one;
  two.threads = 2;
  const FitResult a = fit(test::mdof2_model(prior), {DataSet(data)}, one);
  const FitResult b = fit(test::mdof2_model(prior), {DataSet(data)}, two);
  CHECK(a.start_costs == b.start_costs);
  CHECK(a.best_start == b.best_start);
  CHECK(a.values == b.values);
  FitOptions shared = one;
  shared.cores = std::make_shared<ThreadBudget>(3);
  const FitResult c = fit(test::mdof2_model(prior), {DataSet(data)}, shared);
  CHECK(a.start_costs == c.start_costs);
  CHECK(a.best_start == c.best_start);
  CHECK(a.values == c.values);
  CHECK(shared.cores->free_cores() == 2);
}

TEST_CASE("also_start_at is start 1 of the search", "[fit][frf][global]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(8);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  // No iterations: each start's cost is the cost at the point it starts from.
  FitOptions o;
  o.max_iterations = 0;
  o.starts = 1;
  const double cost_at_truth = fit(test::mdof2_model(truth), {DataSet(data)}, o).start_costs.at(0);
  test::Mdof2Values prior = truth;
  prior.k11 *= 2;
  prior.m2 *= 0.5;
  const test::LinearModel model = test::mdof2_model(prior);
  o.starts = 3;
  const FitResult random = fit(model, {DataSet(data)}, o);
  o.also_start_at = {{"m1", truth.m1}, {"m2", truth.m2},   {"k11", truth.k11}, {"k22", truth.k22},
                     {"k12", truth.k12}, {"c11", truth.c11}, {"c22", truth.c22}};
  const FitResult r = fit(model, {DataSet(data)}, o);
  REQUIRE(r.start_costs.size() == 3);
  CHECK(r.start_costs[0] == random.start_costs[0]);  // the prior, as before
  CHECK(r.start_costs[1] == Approx(cost_at_truth).epsilon(1e-12));
  CHECK(random.start_costs[1] != Approx(cost_at_truth).epsilon(1e-3));  // without it, start 1 is a random draw
  CHECK(r.start_costs[2] == random.start_costs[1]);  // the random starts follow, drawn as before
  o.also_start_at = {{"no_such_parameter", 1.0}};
  CHECK_THROWS_AS(fit(model, {DataSet(data)}, o), FitError);
}

TEST_CASE("further_starts_at follow also_start_at, before the random starts", "[fit][frf][global]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(8);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  FitOptions o;
  o.max_iterations = 0;  // each start's cost is the cost where it starts
  o.agree = 0;           // every start runs (two of them start at the truth)
  o.starts = 1;
  test::Mdof2Values half_k = truth;
  half_k.k11 *= 0.5;
  const double cost_at_truth = fit(test::mdof2_model(truth), {DataSet(data)}, o).start_costs.at(0);
  const double cost_at_half_k = fit(test::mdof2_model(half_k), {DataSet(data)}, o).start_costs.at(0);
  test::Mdof2Values prior = truth;
  prior.k11 *= 2;
  const test::LinearModel model = test::mdof2_model(prior);
  o.starts = 5;
  const FitResult random = fit(model, {DataSet(data)}, o);
  o.also_start_at = {{"k11", truth.k11}};
  o.further_starts_at = {{{"k11", half_k.k11}}, {{"k11", truth.k11}}};
  const FitResult r = fit(model, {DataSet(data)}, o);
  REQUIRE(r.start_costs.size() == 5);
  CHECK(r.start_costs[0] == random.start_costs[0]);
  CHECK(r.start_costs[1] == Approx(cost_at_truth).epsilon(1e-12));
  CHECK(r.start_costs[2] == Approx(cost_at_half_k).epsilon(1e-12));
  CHECK(r.start_costs[3] == Approx(cost_at_truth).epsilon(1e-12));
  CHECK(r.start_costs[4] == random.start_costs[1]);  // the random starts follow, drawn as before
  o.also_start_at.clear();  // without it, the further starts come first
  const FitResult without = fit(model, {DataSet(data)}, o);
  CHECK(without.start_costs[1] == Approx(cost_at_half_k).epsilon(1e-12));
  o.starts = 2;  // `starts` bounds them
  CHECK(fit(model, {DataSet(data)}, o).start_costs.size() == 2);
  o.further_starts_at = {{{"no_such_parameter", 1.0}}};
  CHECK_THROWS_AS(fit(model, {DataSet(data)}, o), FitError);
}

TEST_CASE("settle_first: from the prior and the further starts the others settle first, then all are refined",
          "[fit][frf][global]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(8);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  test::Mdof2Values prior = truth;
  prior.k11 *= 1.3;
  prior.m1 *= 0.8;
  const test::LinearModel model = test::mdof2_model(prior);
  FitOptions o;
  o.starts = 4;
  o.agree = 0;
  o.optimum_start_at = {{"k12", truth.k12}};         // start 1: a point the caller knows to be an optimum
  o.further_starts_at = {{{"k12", 1.5 * truth.k12}}};  // start 2; start 3 is drawn at random
  const FitResult plain = fit(model, {DataSet(data)}, o);
  o.settle_first = {"k12"};
  std::mutex mutex;
  std::map<int, std::set<std::string>> stages;  // by start
  o.progress = [&](const FitProgress& p) {
    std::lock_guard<std::mutex> lock(mutex);
    stages[p.start].insert(p.stage);
  };
  const FitResult settled = fit(model, {DataSet(data)}, o);
  CHECK(settled.cost == Approx(plain.cost).epsilon(1e-6));  // the same optimum
  CHECK(settled.values[4] == Approx(plain.values[4]).epsilon(1e-4));
  const std::set<std::string> settling = {"settle", "refine"}, refining = {"refine"}, searching = {"search", "refine"};
  CHECK(stages[0] == settling);   // the prior: settled (log-ratio search and refinement on all but k12), refined
  CHECK(stages[1] == refining);   // the optimum start: refined only
  CHECK(stages[2] == settling);   // a further start: the others at the prior, as from the prior
  CHECK(stages[3] == searching);  // a random start: every parameter elsewhere, nothing to settle around
  // Nothing left to settle (every free parameter held): the plain fit.
  o.progress = nullptr;
  o.settle_first = {"m1", "m2", "k11", "k22", "k12", "c11", "c22"};
  CHECK(fit(model, {DataSet(data)}, o).start_costs == plain.start_costs);
  o.settle_first = {"no_such_parameter"};
  CHECK_THROWS_AS(fit(model, {DataSet(data)}, o), FitError);
}

TEST_CASE("a memo of local fits gives a later fit's repeated starts their earlier result, and nothing else",
          "[fit][frf][global][memo]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(8);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  const FrfData other_noise = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  test::Mdof2Values prior = truth;
  prior.k11 *= 2;
  prior.m2 *= 0.5;
  const test::LinearModel model = test::mdof2_model(prior);
  std::set<int> ran;  // the starts whose local fits ran (reported progress)
  FitOptions o;
  o.agree = 0;
  o.threads = 1;
  o.progress = [&](const FitProgress& p) {
    if (p.stage == "search" || p.stage == "refine") ran.insert(p.start);
  };
  const auto fit_with = [&](const FitOptions& options, const FrfData& d) {
    ran.clear();
    return fit(model, {DataSet(d)}, options);
  };
  o.starts = 4;
  const FitResult plain = fit_with(o, data);
  o.memo = make_local_fit_memo();
  o.starts = 3;
  const FitResult first = fit_with(o, data);
  CHECK(ran == std::set<int>{0, 1, 2});
  o.starts = 4;
  const FitResult again = fit_with(o, data);
  CHECK(ran == std::set<int>{3});  // only the start not seen before
  CHECK(again.start_costs == plain.start_costs);
  CHECK(again.values == plain.values);
  CHECK(again.cost == plain.cost);
  // Other data: no start is taken from the memo.
  FitOptions no_memo = o;
  no_memo.memo = nullptr;
  const FitResult other_plain = fit_with(no_memo, other_noise);
  const FitResult other = fit_with(o, other_noise);
  CHECK(ran == std::set<int>{0, 1, 2, 3});
  CHECK(other.start_costs == other_plain.start_costs);
  // Another value of a parameter not estimated: the local fits differ, none is taken from the memo.
  o.estimate = {"m1", "m2", "k11", "k22", "k12", "c11", "c22"};
  no_memo.estimate = o.estimate;
  o.values["c12"] = no_memo.values["c12"] = 1.0;
  fit_with(o, data);
  fit_with(o, data);
  CHECK(ran.empty());  // the same fit twice: the second takes every start from the memo
  o.values["c12"] = 2.0;
  const FitResult held_other = fit_with(o, data);
  CHECK(ran == std::set<int>{0, 1, 2, 3});
  no_memo.values["c12"] = o.values["c12"];
  CHECK(held_other.start_costs == fit_with(no_memo, data).start_costs);
}

TEST_CASE("a parameter the data pull beyond its bound is reported at the bound, without a std", "[fit][frf][bounds]") {
  // The truth's k11 lies above the bound: the optimum presses k11 against it. (The spindle demo reported such a
  // mount stiffness as 1e10 +- 3e10, "identifiable".)
  const test::Mdof2Values truth;
  std::mt19937 rng(5);
  const FrfData data = test::mdof2_frf_data(truth, Eigen::VectorXd::LinSpaced(561, 20, 300), 0.01, rng);
  test::LinearModel model = test::mdof2_model(truth, true);
  const double k11_max = 0.8 * truth.k11;
  model.set_bounds(2, 0, k11_max);
  test::Mdof2Values prior = truth;
  prior.k11 = 0.7 * truth.k11;
  FitOptions options;
  options.starts = 2;
  options.values = {{"k11", prior.k11}};
  const FitResult r = fit(model, {DataSet(data)}, options);
  const ParameterEstimate& k11 = r.parameters[2];
  REQUIRE(k11.name == "k11");
  CHECK(k11.at_bound == "upper");
  CHECK(k11.value == k11_max);
  CHECK_FALSE(k11.identifiable);
  CHECK(k11.std == 0);
  CHECK(std::find(r.estimated.begin(), r.estimated.end(), "k11") == r.estimated.end());
  CHECK(r.covariance.rows() == static_cast<Eigen::Index>(r.estimated.size()));
  // The others are ordinary estimates; c22 (0.47 in [0, 1e4], well determined) is near its lower bound, not at it.
  for (const ParameterEstimate& e : r.parameters) {
    if (e.name == "k11" || !e.estimated) continue;
    INFO(e.name << " = " << e.value << " +- " << e.std);
    CHECK(e.at_bound.empty());
    CHECK(e.identifiable);
    CHECK(e.std > 0);
  }
}

TEST_CASE("bound_reached: on a bound only when pressed against it, not when well determined", "[fit][bounds]") {
  ParameterInfo info;
  info.name = "c";
  info.lower = 0;
  info.upper = 1e4;
  const ParameterTransform t = make_parameter_transform(info, 10);
  CHECK(bound_reached(t, 1e4, 1e3) == "upper");
  CHECK(bound_reached(t, 1e4 - 1e-3, 1.0) == "upper");
  CHECK(bound_reached(t, 1e-3, 1.0) == "lower");
  CHECK(bound_reached(t, 1e-3, 1e-4) == "");        // well determined: an interior estimate
  CHECK(bound_reached(t, 0.47, 1.0) == "");         // farther than 1e-6 of the interval from the bound
  CHECK(bound_reached(t, 5000, 1e9) == "");
  ParameterInfo free_info;
  free_info.name = "x";
  CHECK(bound_reached(make_parameter_transform(free_info, 1), 0, 1) == "");  // no bounds
}

TEST_CASE("unidentifiable_to_prior: where a parameter lost at the estimate is held while the rest are refitted",
          "[fit][frf][identifiability]") {
  // d1 sees a mass on a spring (m1, k11, c11) and, in the model, a second oscillator that the same force drives through
  // a gain b (mass m2, free of bounds; stiffness k2; undamped): it adds b / (k2 - w^2 m2) to d1. The data add a
  // constant compliance instead, which the model can reach only at m2 = 0: the search takes m2 there (to within the
  // noise, 1e-9), where m2 no longer acts and b and k2 act as their ratio alone. m2 and one of b, k2 are lost at the
  // estimate, whichever way the search went. Back at its prior m2 acts again, and the refit of the others cannot make
  // up for it; held where the search left it, the refit starts at the others' optimum.
  const double m1 = 1.39, k11 = 1.38e6, c11 = 13.42;
  const Eigen::VectorXd f = frequencies();
  FrfData data;
  data.file = "compliance.csv";
  data.f_hz = f;
  FrfChannel ch;
  ch.output = "d1";
  ch.input = "F1";
  ch.values.resize(f.size());
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    const double w = 2 * M_PI * f[k];
    ch.values[k] = 1.0 / std::complex<double>(k11 - w * w * m1, w * c11) + 1 / (4 * k11);
  }
  std::mt19937 rng(3);
  test::add_relative_noise(ch.values, 1e-9, rng);
  data.channels.push_back(ch);

  test::LinearModel model("compliance", 2, {"F1"}, {"d1"});
  using R = ParameterRole;
  using M = test::LinearModel;
  const double inf = std::numeric_limits<double>::infinity();
  const double m2_prior = 0.05;  // the oscillator's resonance at 1450 Hz, above the band
  const int p_m1 = model.parameter("m1", 1.2 * m1, R::Estimate);
  const int p_k11 = model.parameter("k11", 0.9 * k11, R::Estimate);
  const int p_c11 = model.parameter("c11", 1.3 * c11, R::Estimate);
  const int p_m2 = model.parameter("m2", m2_prior, R::Estimate, -inf, inf);
  const int p_k2 = model.parameter("k2", 3 * k11, R::Estimate);
  const int p_b = model.parameter("b", 1, R::Estimate);
  model.linear(M::M, p_m1, 0, 0, 1);
  model.element(M::K, p_k11, 0, -1);
  model.element(M::C, p_c11, 0, -1);
  model.linear(M::M, p_m2, 1, 1, 1);
  model.element(M::K, p_k2, 1, -1);
  model.constant(M::B, 0, 0, 1);
  model.linear(M::B, p_b, 1, 0, 1);
  model.constant(M::Cd, 0, 0, 1);
  model.constant(M::Cd, 0, 1, 1);

  FitOptions options;
  options.starts = 1;
  for (const bool to_prior : {true, false}) {
    INFO("unidentifiable_to_prior " << to_prior);
    options.unidentifiable_to_prior = to_prior;
    const FitResult r = fit(model, {DataSet(data)}, options);
    std::map<std::string, const ParameterEstimate*> lost;
    for (const ParameterEstimate& e : r.parameters)
      if (!e.estimated) lost[e.name] = &e;
    REQUIRE(lost.count("m2"));
    CHECK(lost.size() == 2);
    CHECK(lost.count("b") + lost.count("k2") == 1);
    const double m2 = lost.at("m2")->value;
    INFO("m2 = " << m2);
    const double searched = r.start_costs[static_cast<std::size_t>(r.best_start)];
    if (to_prior) {
      CHECK(m2 == m2_prior);
      CHECK(r.cost > 100 * searched);  // back at its prior m2 acts again, and the others cannot make up for it
    } else {
      CHECK(std::abs(m2) < 1e-6);            // where the search left it
      CHECK(r.cost / searched - 1 <= 1e-9);  // not above the search's cost (evaluated again: rounding)
    }
  }
}
