// The direct method on hand-assembled models with data from closed forms (test_support.hpp: mdof2's transfer
// functions from docs/reference-models.md, an exact modal zero-order-hold simulation), independent of the code
// under test.
#include "../estimation/test_support.hpp"

#include "mbgen/methods/direct.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>

using namespace mbgen;

namespace {

Eigen::VectorXd frequencies() { return Eigen::VectorXd::LinSpaced(1561, 10, 400); }  // truthgen's grid

// The model's prior 3-10 % off the truth, signs mixed.
test::Mdof2Values offset(const test::Mdof2Values& t) {
  test::Mdof2Values p = t;
  p.m1 *= 1.05; p.m2 *= 0.93; p.k11 *= 1.08; p.k22 *= 0.95; p.k12 *= 1.1; p.c11 *= 0.92; p.c22 *= 1.07;
  return p;
}

std::vector<double> values_of(const test::Mdof2Values& v) { return {v.m1, v.m2, v.k11, v.k22, v.k12, v.c11, v.c22}; }

}  // namespace

TEST_CASE("direct, noiseless FRFs: the parameters exactly", "[direct][frf]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(1);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.0, rng);
  const test::LinearModel model = test::mdof2_model(offset(truth), true);
  const FitResult r = fit_direct(model, {DataSet(data)});
  CHECK(r.method == "direct");
  CHECK(r.converged);
  const std::vector<double> t = values_of(truth);
  REQUIRE(r.parameters.size() == t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    INFO(r.parameters[i].name << " = " << r.parameters[i].value << ", truth " << t[i]);
    CHECK(std::abs(r.parameters[i].value - t[i]) < 1e-9 * t[i]);
    CHECK(r.parameters[i].identifiable);
  }
  CHECK(r.nrmse < 1e-8);
  const auto details = nlohmann::json::parse(r.method_details.at("direct"));
  CHECK(details.at("linear_in_parameters").get<bool>());
  CHECK(details.at("coordinates") == nlohmann::json({"q0", "q1"}));
}

TEST_CASE("experiment: direct FRF bias", "[.experiment]") {
  const test::Mdof2Values truth;
  const std::vector<double> t = values_of(truth);
  std::vector<double> sum(t.size()), sum_ls(t.size()), sum_oe(t.size());
  const int runs = 10;
  for (int s = 0; s < runs; ++s) {
    std::mt19937 rng(100 + s);
    const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
    const test::LinearModel model = test::mdof2_model(offset(truth), true);
    const FitResult r = fit_direct(model, {DataSet(data)});
    const auto details = nlohmann::json::parse(r.method_details.at("direct"));
    std::cout << details.dump() << "\n";
    for (std::size_t i = 0; i < t.size(); ++i) {
      sum[i] += (r.parameters[i].value - t[i]) / t[i];
      sum_ls[i] += (details["least_squares_estimate"][r.parameters[i].name].get<double>() - t[i]) / t[i];
    }
    FitOptions o;
    o.starts = 1;
    const FitResult oe = fit(model, {DataSet(data)}, o);
    for (std::size_t i = 0; i < t.size(); ++i) sum_oe[i] += (oe.parameters[i].value - t[i]) / t[i];
  }
  for (std::size_t i = 0; i < t.size(); ++i)
    std::cout << i << " gtls " << sum[i] / runs << " ls " << sum_ls[i] / runs << " oe " << sum_oe[i] / runs << "\n";
}
