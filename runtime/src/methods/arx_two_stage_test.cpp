// fit_arx_two_stage on mdof2 records simulated in the test by exact modal superposition (test_support.hpp), an
// independent route from the runtime's matrix-exponential discretisation. The masses are known, as the method needs.
#include "mbgen/methods/arx_two_stage.hpp"

#include "mbgen_test/estimation.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>

using namespace mbgen;

namespace {

// mdof2 with m1, m2 known at the truth's values, the stiffnesses and dampings to estimate from the nominal ones.
test::LinearModel known_mass_model(const test::Mdof2Values& truth) {
  test::Mdof2Values prior;  // nominal
  prior.m1 = truth.m1;
  prior.m2 = truth.m2;
  test::LinearModel m = test::mdof2_model(prior);
  return m;
}

FitOptions masses_known() {
  FitOptions o;
  o.estimate = {"k11", "k22", "k12", "c11", "c22"};
  return o;
}

test::Mdof2Values truth() {
  test::Mdof2Values v;
  v.m1 = 1.262;
  v.m2 = 1.022;
  v.k11 = 1.30e6;
  v.k22 = 2.596e5;
  v.k12 = 1.098e5;
  v.c11 = 14.39;
  v.c22 = 0.4906;
  return v;
}

double relative_error(const FitResult& r, const std::string& name, double truth) {
  for (const ParameterEstimate& e : r.parameters)
    if (e.name == name) return std::abs(e.value / truth - 1);
  FAIL("no parameter " << name);
  return 0;
}

}  // namespace

TEST_CASE("arx-two-stage on noise-free records: K and C of mdof2", "[arx-two-stage]") {
  const test::Mdof2Values v = truth();
  std::mt19937 rng(5);
  // Sampling 4096 Hz (the upper mode at 0.04 of it), 2 s; no noise.
  const TimeRecord record = test::mdof2_time_record(v, 8192, 1.0 / 4096, 0.0, rng);
  const test::LinearModel model = known_mass_model(v);
  const FitResult r = fit_arx_two_stage(model, {DataSet(record)}, masses_known());
  CHECK(r.method == "arx-two-stage");
  // Without noise the ARX of order 2 is the exact sampled system; what remains is the finite differences' error,
  // 4th order: (w dt)^4 / 30 ~ 1.4e-4 at the upper mode. Measured: K within 7e-5, C within 1e-5.
  INFO("errors: k11 " << relative_error(r, "k11", v.k11) << ", k22 " << relative_error(r, "k22", v.k22) << ", k12 "
                      << relative_error(r, "k12", v.k12) << ", c11 " << relative_error(r, "c11", v.c11) << ", c22 "
                      << relative_error(r, "c22", v.c22));
  CHECK(relative_error(r, "k11", v.k11) < 2e-4);
  CHECK(relative_error(r, "k22", v.k22) < 2e-4);
  CHECK(relative_error(r, "k12", v.k12) < 2e-4);
  CHECK(relative_error(r, "c11", v.c11) < 1e-4);
  CHECK(relative_error(r, "c22", v.c22) < 1e-4);
  for (const ParameterEstimate& e : r.parameters) CHECK(std::isnan(e.std));  // no std claimed (see the header)
  // The identified modes against the truth's, from the state matrix written out here.
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  A(0, 2) = A(1, 3) = 1;
  A(2, 0) = -(v.k11 + v.k12) / v.m1;
  A(2, 1) = v.k12 / v.m1;
  A(3, 0) = v.k12 / v.m2;
  A(3, 1) = -(v.k22 + v.k12) / v.m2;
  A(2, 2) = -v.c11 / v.m1;
  A(3, 3) = -v.c22 / v.m2;
  std::vector<std::complex<double>> poles;
  const Eigen::EigenSolver<Eigen::Matrix4d> solver(A);  // kept: eigenvalues() refers into it
  for (const auto& l : solver.eigenvalues())
    if (l.imag() > 0) poles.push_back(l);
  std::sort(poles.begin(), poles.end(), [](auto a, auto b) { return std::abs(a) < std::abs(b); });
  const nlohmann::json j = nlohmann::json::parse(r.method_details.at("arx_two_stage"));
  REQUIRE(j["modes"].size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    const double f = std::abs(poles[i]) / (2 * std::acos(-1.0)), zeta = -poles[i].real() / std::abs(poles[i]);
    CHECK(j["modes"][i]["f_hz"].get<double>() == Approx(f).epsilon(1e-4));
    CHECK(j["modes"][i]["zeta"].get<double>() == Approx(zeta).epsilon(1e-3));
    CHECK(j["modes"][i]["zeta_modal"].get<double>() == Approx(zeta).epsilon(2e-2));  // proportional-damping reading
  }
}

TEST_CASE("arx-two-stage: the error grows with the noise", "[arx-two-stage]") {
  const test::Mdof2Values v = truth();
  const test::LinearModel model = known_mass_model(v);
  double previous = 0;
  for (double noise : {0.001, 0.01, 0.1}) {  // 60, 40, 20 dB; the same force and noise draws
    std::mt19937 rng(9);
    const TimeRecord record = test::mdof2_time_record(v, 8192, 1.0 / 4096, noise, rng);
    const FitResult r = fit_arx_two_stage(model, {DataSet(record)}, masses_known());
    const double error =
        (relative_error(r, "k11", v.k11) + relative_error(r, "k22", v.k22) + relative_error(r, "k12", v.k12)) / 3;
    INFO("noise " << noise << ": mean stiffness error " << error);
    CHECK(error > previous);
    previous = error;
  }
}

TEST_CASE("arx-two-stage refuses what it cannot use", "[arx-two-stage]") {
  const test::Mdof2Values v = truth();
  std::mt19937 rng(5);
  const TimeRecord record = test::mdof2_time_record(v, 512, 1.0 / 1024, 0.01, rng);
  SECTION("estimated masses") {
    const test::LinearModel model = test::mdof2_model();
    CHECK_THROWS_WITH(fit_arx_two_stage(model, {DataSet(record)}),
                      Catch::Contains("needs the mass matrix known") && Catch::Contains("m1, m2"));
  }
  SECTION("a coordinate not measured") {
    TimeRecord only_d1 = record;
    only_d1.signals.pop_back();  // d2
    const test::LinearModel model = known_mass_model(v);
    CHECK_THROWS_WITH(fit_arx_two_stage(model, {DataSet(only_d1)}, masses_known()),
                      Catch::Contains("needs every coordinate measured") && Catch::Contains("(d1)") &&
                          Catch::Contains("1 of the 2 coordinates: q1"));
  }
  SECTION("FRF data") {
    const FrfData frf = test::mdof2_frf_data(v, Eigen::VectorXd::LinSpaced(50, 10, 400), 0.01, rng);
    const test::LinearModel model = known_mass_model(v);
    CHECK_THROWS_WITH(fit_arx_two_stage(model, {DataSet(frf)}, masses_known()),
                      Catch::Contains("--method arx-two-stage needs time records"));
  }
}
