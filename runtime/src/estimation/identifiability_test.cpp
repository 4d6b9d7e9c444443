// Unidentifiable parameters: two springs that only act as a sum, and an uncoupled block the data never excite.
// Also the identifiability analysis on hand-made Jacobians with known rank.
#include "mbgen_test/estimation.hpp"

#include "mbgen/estimation/fit.hpp"
#include "mbgen/estimation/identifiability.hpp"

#include <catch2/catch.hpp>

using namespace mbgen;

TEST_CASE("analysis of hand-made Jacobians", "[identifiability]") {
  Eigen::MatrixXd J(4, 4);
  // column 2 = 2 * column 0 (a scaled duplicate), column 3 = 0.
  J << 1, 0, 2, 0,
       0, 1, 0, 0,
       1, 1, 2, 0,
       3, 0, 6, 0;
  const IdentifiabilityAnalysis a = analyse_identifiability(J);
  CHECK(a.identifiable == std::vector<bool>{true, true, false, false});
  CHECK(a.rank() == 2);
  CHECK(a.confounded_with[0] == std::vector<int>{2});
  CHECK(a.confounded_with[2] == std::vector<int>{0});
  CHECK(a.confounded_with[3].empty());
  REQUIRE(a.singular_values.size() == 3);  // of the three non-zero columns
  CHECK(a.singular_values[2] < 1e-12);
  // More parameters than residuals: rank at most the row count, never a crash.
  const IdentifiabilityAnalysis wide = analyse_identifiability(Eigen::MatrixXd::Ones(1, 3));
  CHECK(wide.rank() == 1);
  CHECK(analyse_identifiability(Eigen::MatrixXd::Zero(5, 2)).rank() == 0);
}

TEST_CASE("two parallel springs between the same points are not separately identifiable", "[fit][identifiability]") {
  // mdof2 with the helix split into k12a + k12b (truth 0.08e6 + 0.04e6 = k12).
  using R = ParameterRole;
  const test::Mdof2Values truth;
  test::LinearModel model("mdof2_parallel", 2, {"F1"}, {"d1", "d2"});
  const int m1 = model.parameter("m1", truth.m1 * 1.05, R::Estimate), m2 = model.parameter("m2", truth.m2, R::Known);
  const int k11 = model.parameter("k11", truth.k11 * 0.95, R::Estimate);
  const int k22 = model.parameter("k22", truth.k22, R::Estimate);
  const int k12a = model.parameter("k12a", 0.05e6, R::Estimate), k12b = model.parameter("k12b", 0.05e6, R::Estimate);
  const int c11 = model.parameter("c11", truth.c11, R::Estimate), c22 = model.parameter("c22", truth.c22, R::Estimate);
  model.linear(test::LinearModel::M, m1, 0, 0, 1);
  model.linear(test::LinearModel::M, m2, 1, 1, 1);
  model.element(test::LinearModel::K, k11, 0, -1);
  model.element(test::LinearModel::K, k22, 1, -1);
  model.element(test::LinearModel::K, k12a, 0, 1);
  model.element(test::LinearModel::K, k12b, 0, 1);
  model.element(test::LinearModel::C, c11, 0, -1);
  model.element(test::LinearModel::C, c22, 1, -1);
  model.constant(test::LinearModel::B, 0, 0, 1);
  model.constant(test::LinearModel::Cd, 0, 0, 1);
  model.constant(test::LinearModel::Cd, 1, 1, 1);
  std::mt19937 rng(21);
  const FrfData data = test::mdof2_frf_data(truth, Eigen::VectorXd::LinSpaced(1121, 20, 300), 0.01, rng);
  FitOptions options;
  options.starts = 2;
  const FitResult r = fit(model, {DataSet(data)}, options);
  REQUIRE(r.parameters.size() == 7);
  const ParameterEstimate& a = r.parameters[3];
  const ParameterEstimate& b = r.parameters[4];
  REQUIRE(a.name == "k12a");
  REQUIRE(b.name == "k12b");
  // One of the pair is kept at its prior, reported unidentifiable; the other carries the sum.
  CHECK(a.identifiable);
  CHECK_FALSE(b.identifiable);
  CHECK_FALSE(b.estimated);
  CHECK(b.value == 0.05e6);
  CHECK(b.std == 0);
  CHECK(a.confounded_with == std::vector<std::string>{"k12b"});
  CHECK(b.confounded_with == std::vector<std::string>{"k12a"});
  CHECK(a.value + b.value == Approx(truth.k12).epsilon(0.01));
  CHECK(r.estimated.size() == 6);
  CHECK(r.covariance.rows() == 6);
  CHECK(r.covariance.allFinite());
}

TEST_CASE("an uncoupled block the data do not excite is reported unidentifiable", "[fit][identifiability]") {
  // mdof2 plus a third mass on its own spring-damper, not connected to the others; only d1/F1 and d2/F1
  // are measured: the Jacobian columns of m3, k33, c33 are exactly zero.
  using R = ParameterRole;
  const test::Mdof2Values truth;
  test::LinearModel model("mdof2_plus", 3, {"F1", "F3"}, {"d1", "d2", "d3"});
  const int m1 = model.parameter("m1", truth.m1 * 1.05, R::Estimate), m2 = model.parameter("m2", truth.m2, R::Estimate);
  const int k11 = model.parameter("k11", truth.k11, R::Estimate), k22 = model.parameter("k22", truth.k22, R::Estimate);
  const int k12 = model.parameter("k12", truth.k12 * 0.9, R::Estimate);
  const int c11 = model.parameter("c11", truth.c11, R::Estimate), c22 = model.parameter("c22", truth.c22, R::Estimate);
  const int m3 = model.parameter("m3", 2.0, R::Estimate), k33 = model.parameter("k33", 5e5, R::Estimate);
  const int c33 = model.parameter("c33", 3.0, R::Estimate);
  model.linear(test::LinearModel::M, m1, 0, 0, 1);
  model.linear(test::LinearModel::M, m2, 1, 1, 1);
  model.linear(test::LinearModel::M, m3, 2, 2, 1);
  model.element(test::LinearModel::K, k11, 0, -1);
  model.element(test::LinearModel::K, k22, 1, -1);
  model.element(test::LinearModel::K, k12, 0, 1);
  model.element(test::LinearModel::K, k33, 2, -1);
  model.element(test::LinearModel::C, c11, 0, -1);
  model.element(test::LinearModel::C, c22, 1, -1);
  model.element(test::LinearModel::C, c33, 2, -1);
  model.constant(test::LinearModel::B, 0, 0, 1);
  model.constant(test::LinearModel::B, 2, 1, 1);
  for (int i = 0; i < 3; ++i) model.constant(test::LinearModel::Cd, i, i, 1);
  std::mt19937 rng(22);
  const FrfData data = test::mdof2_frf_data(truth, Eigen::VectorXd::LinSpaced(1121, 20, 300), 0.01, rng);
  FitOptions options;
  options.starts = 2;
  const FitResult r = fit(model, {DataSet(data)}, options);
  REQUIRE(r.parameters.size() == 10);
  for (const auto& e : r.parameters) {
    INFO(e.name << " = " << e.value << " +- " << e.std);
    const bool third = e.name == "m3" || e.name == "k33" || e.name == "c33";
    CHECK(e.identifiable == !third);
    if (third) {
      CHECK(e.value == e.prior);
      CHECK(e.confounded_with.empty());
    }
  }
  CHECK(r.parameters[0].value == Approx(truth.m1).epsilon(0.01));
  CHECK(r.parameters[4].value == Approx(truth.k12).epsilon(0.01));
}

TEST_CASE("a parameter set by every data set is unidentifiable in the shared vector", "[fit][identifiability][sets]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(23);
  FrfData data = test::mdof2_frf_data(truth, Eigen::VectorXd::LinSpaced(1121, 20, 300), 0.01, rng);
  data.set["m2"] = SetValue{"1.09", 1.09};
  test::Mdof2Values prior = truth;
  prior.m2 = 3.0;
  FitOptions options;
  options.starts = 1;
  const FitResult r = fit(test::mdof2_model(prior), {DataSet(data)}, options);
  CHECK_FALSE(r.parameters[1].identifiable);
  CHECK(r.parameters[1].value == 3.0);
  CHECK(r.parameters[0].value == Approx(truth.m1).epsilon(0.01));
}

TEST_CASE("bad input is rejected with a message naming the data set", "[fit][errors]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(24);
  FrfData data = test::mdof2_frf_data(truth, Eigen::VectorXd::LinSpaced(11, 20, 300), 0.01, rng);
  data.file = "bad.csv";
  FrfData unknown_set = data;
  unknown_set.set["nope"] = SetValue{"1", 1};
  CHECK_THROWS_WITH(fit(test::mdof2_model(), {DataSet(unknown_set)}), Catch::Contains("bad.csv") && Catch::Contains("nope"));
  FrfData unknown_channel = data;
  unknown_channel.channels[0].output = "d9";
  CHECK_THROWS_WITH(fit(test::mdof2_model(), {DataSet(unknown_channel)}), Catch::Contains("bad.csv") && Catch::Contains("d9"));
  FitOptions bad;
  bad.estimate = {"k99"};
  CHECK_THROWS_AS(fit(test::mdof2_model(), {DataSet(data)}, bad), FitError);
  CHECK_THROWS_AS(fit(test::mdof2_model(), {}), FitError);
}
