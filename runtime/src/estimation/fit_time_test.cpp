// Time-domain output-error fits of mdof2 ("one step" method) on records simulated exactly by modal
// superposition in the test (test_support.hpp), independent of the estimator's own discretisation.
#include "mbgen_test/estimation.hpp"

#include "mbgen/estimation/fit.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mbgen;

namespace {

const char* const kNames[] = {"m1", "m2", "k11", "k22", "k12", "c11", "c22"};

Eigen::VectorXd truth_vector(const test::Mdof2Values& v) {
  Eigen::VectorXd p(8);
  p << v.m1, v.m2, v.k11, v.k22, v.k12, v.c11, v.c22, v.c12;
  return p;
}

FitOptions quick_options() {
  FitOptions o;
  o.starts = 1;
  return o;
}

}  // namespace

TEST_CASE("time-domain fit of mdof2 at 40 dB SNR recovers the seven parameters within 3 std", "[fit][time]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(7);
  const TimeRecord record = test::mdof2_time_record(truth, 4000, 1.0 / 2000, 0.01, rng);
  // Prior 10 % off in every parameter.
  test::Mdof2Values prior = truth;
  prior.m1 *= 1.1; prior.m2 *= 0.9; prior.k11 *= 1.1; prior.k22 *= 0.9; prior.k12 *= 1.1;
  prior.c11 *= 0.9; prior.c22 *= 1.1;
  const test::LinearModel model = test::mdof2_model(prior);
  const FitResult r = fit(model, {DataSet(record)}, quick_options());
  REQUIRE(r.parameters.size() == 7);
  const Eigen::VectorXd p = truth_vector(truth);
  for (int i = 0; i < 7; ++i) {
    const ParameterEstimate& e = r.parameters[static_cast<std::size_t>(i)];
    CHECK(e.name == kNames[i]);
    CHECK(e.identifiable);
    CHECK(e.std > 0);
    INFO(e.name << " = " << e.value << " +- " << e.std << ", truth " << p[i]);
    CHECK(std::abs(e.value - p[i]) < 3 * e.std);
  }
  CHECK(r.converged);
  CHECK(r.method == "time-output-error");
  CHECK(r.nrmse < 0.02);  // noise is 1 % of the RMS: nrmse ~ 0.01
  CHECK(r.nrmse > 0.005);
  REQUIRE(r.modes.size() == 2);
  CHECK(r.modes[0].f_hz == Approx(89.72).margin(0.05));
  CHECK(r.modes[1].f_hz == Approx(166.29).margin(0.1));
}

TEST_CASE("slow: reported standard deviations match the scatter over 30 noise realisations", "[fit][time][slow]") {
  const test::Mdof2Values truth;
  const test::LinearModel model = test::mdof2_model(truth);
  const int realisations = 30;
  Eigen::MatrixXd estimates(realisations, 7), stds(realisations, 7);
  for (int k = 0; k < realisations; ++k) {
    std::mt19937 rng(1000 + static_cast<unsigned>(k));
    const TimeRecord record = test::mdof2_time_record(truth, 2000, 1.0 / 2000, 0.01, rng);
    const FitResult r = fit(model, {DataSet(record)}, quick_options());
    for (int i = 0; i < 7; ++i) {
      estimates(k, i) = r.parameters[static_cast<std::size_t>(i)].value;
      stds(k, i) = r.parameters[static_cast<std::size_t>(i)].std;
    }
  }
  for (int i = 0; i < 7; ++i) {
    const double mean = estimates.col(i).mean();
    const double scatter = std::sqrt((estimates.col(i).array() - mean).square().sum() / (realisations - 1));
    const double reported = stds.col(i).mean();
    INFO(kNames[i] << ": scatter " << scatter << ", mean reported std " << reported);
    CHECK(reported / scatter < 1.5);
    CHECK(scatter / reported < 1.5);
  }
}

TEST_CASE("records with and without an added mass on mass2 are fitted jointly", "[fit][time][sets]") {
  const test::Mdof2Values truth;
  // The model gets an extra known parameter m_add on mass2, default 0; the second record sets it to 0.75.
  test::Mdof2Values prior = truth;
  prior.m1 *= 1.05; prior.m2 *= 0.95; prior.k12 *= 1.05;
  test::LinearModel model = test::mdof2_model(prior);
  const int m_add = model.parameter("m_add", 0.0, ParameterRole::Known);
  model.linear(test::LinearModel::M, m_add, 1, 1, 1);
  std::mt19937 rng(11);
  TimeRecord plain = test::mdof2_time_record(truth, 3000, 1.0 / 2000, 0.01, rng);
  TimeRecord loaded = test::mdof2_time_record(truth, 3000, 1.0 / 2000, 0.01, rng, 0.75);
  loaded.file = "loaded.csv";
  loaded.set["m_add"] = SetValue{"0.75", 0.75};
  const FitResult joint = fit(model, {DataSet(plain), DataSet(loaded)}, quick_options());
  const Eigen::VectorXd p = truth_vector(truth);
  for (int i = 0; i < 7; ++i) {
    const ParameterEstimate& e = joint.parameters[static_cast<std::size_t>(i)];
    INFO(e.name << " = " << e.value << " +- " << e.std);
    CHECK(std::abs(e.value - p[i]) < 3 * e.std);
  }
  // m_add stays at its default in the shared vector: it is known, and only the set applies it.
  CHECK(joint.values[m_add] == 0.0);
  // Fitting the loaded record while pretending the mass is absent is visibly worse.
  TimeRecord unlabelled = loaded;
  unlabelled.set.clear();
  const FitResult wrong = fit(model, {DataSet(plain), DataSet(unlabelled)}, quick_options());
  CHECK(wrong.cost > 10 * joint.cost);
}

TEST_CASE("slow: time records: the multi-start search on their H1 reaches the time-domain optimum from priors within x3",
          "[fit][time][global][slow]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(11);
  const TimeRecord record = test::mdof2_time_record(truth, 4000, 1.0 / 2000, 0.01, rng);
  const FitResult reference = fit(test::mdof2_model(truth), {DataSet(record)}, quick_options());
  std::mt19937 prior_rng(17);
  std::uniform_real_distribution<double> exponent(-1, 1);
  for (int run = 0; run < 5; ++run) {
    test::Mdof2Values prior = truth;
    for (double* x : {&prior.m1, &prior.m2, &prior.k11, &prior.k22, &prior.k12, &prior.c11, &prior.c22})
      *x *= std::pow(3.0, exponent(prior_rng));
    FitOptions o;
    o.seed = static_cast<unsigned>(run + 1);
    o.starts = 8;
    const FitResult r = fit(test::mdof2_model(prior), {DataSet(record)}, o);
    INFO("run " << run << ": cost " << r.cost << " vs reference " << reference.cost << ", best start " << r.best_start);
    CHECK(r.method == "time-output-error");
    CHECK(r.cost == Approx(reference.cost).epsilon(1e-6));
    for (std::size_t i = 0; i < 7; ++i)
      CHECK(r.parameters[i].value == Approx(reference.parameters[i].value).epsilon(1e-4));
  }
}
