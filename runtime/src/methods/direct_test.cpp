// The direct method on hand-assembled models with data from closed forms (test_support.hpp: mdof2's transfer
// functions from docs/reference-models.md, an exact modal zero-order-hold simulation), independent of the code
// under test.
#include "mbgen_test/estimation.hpp"

#include "mbgen/methods/direct.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

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

double largest_relative_error(const FitResult& r, const std::vector<double>& truth) {
  double worst = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) worst = std::max(worst, std::abs(r.parameters[i].value / truth[i] - 1));
  return worst;
}

// mdof2 with k11 = r11^2: M, C, K not linear in the parameters (the direct method iterates, Gauss-Newton).
class SquaredStiffness : public Model {
 public:
  explicit SquaredStiffness(const test::Mdof2Values& prior) : base_(test::mdof2_model(prior, true)) {
    info_ = base_.info();
    info_.parameters[2].name = "r11";
    info_.parameters[2].value = std::sqrt(prior.k11);
    info_.parameters[2].upper = std::sqrt(info_.parameters[2].upper);
  }
  const ModelInfo& info() const override { return info_; }
  void evaluate(const Eigen::VectorXd& p, ModelMatrices& out) const override { base_.evaluate(squared(p), out); }
  void derivatives(const Eigen::VectorXd& p, ModelDerivatives& out) const override {
    base_.derivatives(squared(p), out);
    for (auto* list : {&out.M, &out.C, &out.K, &out.B, &out.Cd, &out.Cv, &out.Ca})
      for (auto& e : *list)
        if (e.param == 2) e.value *= 2 * p[2];
  }

 private:
  static Eigen::VectorXd squared(Eigen::VectorXd p) {
    p[2] *= p[2];
    return p;
  }
  test::LinearModel base_;
  ModelInfo info_;
};

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

TEST_CASE("direct, noiseless FRFs of a model not linear in its parameters: Gauss-Newton, exact", "[direct][frf]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(1);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.0, rng);
  const SquaredStiffness model(offset(truth));
  const FitResult r = fit_direct(model, {DataSet(data)});
  CHECK(r.converged);
  std::vector<double> t = values_of(truth);
  t[2] = std::sqrt(t[2]);
  CHECK(largest_relative_error(r, t) < 1e-9);
  CHECK_FALSE(nlohmann::json::parse(r.method_details.at("direct")).at("linear_in_parameters").get<bool>());
}

TEST_CASE("direct, noiseless time record: exact up to the record's aliasing", "[direct][time]") {
  // The sampled record determines the continuous spectra up to aliasing, which falls as (f / fs)^3 for a
  // zero-order-hold force: halving the sample interval divides the error by about 8.
  const test::Mdof2Values truth;
  const std::vector<double> t = values_of(truth);
  std::vector<double> error;
  for (double h : {1.0 / 4096, 1.0 / 8192}) {
    std::mt19937 rng(7);
    const TimeRecord rec = test::mdof2_time_record(truth, static_cast<Eigen::Index>(2 / h), h, 0.0, rng);
    const FitResult r = fit_direct(test::mdof2_model(offset(truth), true), {DataSet(rec)});
    CHECK(r.converged);
    error.push_back(largest_relative_error(r, t));
    INFO("h " << h << ": largest relative error " << error.back());
  }
  CHECK(error[0] < 5e-5);
  CHECK(error[1] < 5e-6);
}

TEST_CASE("direct, 40 dB FRFs: instrumental variables remove ordinary least squares' bias", "[direct][frf]") {
  // Ten noise draws of the same truth. Ordinary LS on the noisy receptances shrinks m2, k22, k12 by about 0.5 %
  // (errors in variables); IV is unbiased to within the scatter and agrees with the output-error fit on average.
  const test::Mdof2Values truth;
  const std::vector<double> t = values_of(truth);
  const int runs = 10;
  std::vector<double> mean(t.size()), mean_ls(t.size()), mean_oe(t.size());
  for (int s = 0; s < runs; ++s) {
    std::mt19937 rng(static_cast<unsigned>(100 + s));
    const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
    const test::LinearModel model = test::mdof2_model(offset(truth), true);
    const FitResult r = fit_direct(model, {DataSet(data)});
    const auto details = nlohmann::json::parse(r.method_details.at("direct"));
    INFO(details.dump());
    REQUIRE(details.at("solver") == "instrumental variables");
    REQUIRE(details.at("other_estimate").at("solver") == "least squares");
    // The noise level frf_noise estimates from the data is the noise: the whitened equation error's variance 1.
    CHECK(std::abs(details.at("noise_scale").get<double>() - 1) < 0.05);
    FitOptions o;
    o.starts = 1;
    const FitResult oe = fit(model, {DataSet(data)}, o);
    for (std::size_t i = 0; i < t.size(); ++i) {
      const std::string& name = r.parameters[i].name;
      mean[i] += (r.parameters[i].value / t[i] - 1) / runs;
      mean_ls[i] += (details["other_estimate"]["values"][name].get<double>() / t[i] - 1) / runs;
      mean_oe[i] += (oe.parameters[i].value / t[i] - 1) / runs;
    }
  }
  for (std::size_t i = 0; i < t.size(); ++i) {
    INFO(i << ": mean relative error IV " << mean[i] << ", LS " << mean_ls[i] << ", output error " << mean_oe[i]);
    CHECK(std::abs(mean[i]) < 1.5e-3);
    CHECK(std::abs(mean[i] - mean_oe[i]) < 2e-4);
  }
  CHECK(mean_ls[1] < -3e-3);  // m2
  CHECK(mean_ls[3] < -3e-3);  // k22
  CHECK(mean_ls[4] < -2e-3);  // k12
}

TEST_CASE("direct: outputs that cannot give every coordinate are refused, naming them", "[direct]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(1);
  FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  data.channels.pop_back();  // d1/F1 only
  const test::LinearModel model = test::mdof2_model(truth, true);
  CHECK_THROWS_WITH(fit_direct(model, {DataSet(data)}),
                    Catch::Contains("mdof2-synthetic.csv: error: --method direct needs the motion of every coordinate "
                                    "the input F1 moves (2: q0, q1), but the outputs measured (1: d1) cannot give q1"));
}

TEST_CASE("direct: a bound the equations pull past holds the parameter there, reported", "[direct]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(1);
  const FrfData data = test::mdof2_frf_data(truth, frequencies(), 0.01, rng);
  test::Mdof2Values prior = offset(truth);
  prior.k11 = 1.2e6;
  test::LinearModel model = test::mdof2_model(prior, true);
  model.set_bounds(2, 0, 1.3e6);  // k11's truth is 1.38e6
  const FitResult r = fit_direct(model, {DataSet(data)});
  const ParameterEstimate& k11 = r.parameters[2];
  CHECK(k11.at_bound == "upper");
  CHECK(k11.value == 1.3e6);
  CHECK_FALSE(k11.identifiable);
  CHECK(std::find(r.estimated.begin(), r.estimated.end(), "k11") == r.estimated.end());
  CHECK(r.covariance.rows() == 6);
}
