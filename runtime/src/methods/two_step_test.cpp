// The two-step method on noiseless data made by routes independent of it (test_support.hpp: the closed-form
// transfer functions of mdof2, an exact modal zero-order-hold simulation): both steps must then recover the truth
// exactly, up to rounding. Noisy data and the examples: tests/two_step (truthgen, the command line).
#include "mbgen_test/estimation.hpp"

#include "mbgen/methods/two_step.hpp"

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace mbgen;

namespace {

// A truth 3-10 % off the model's defaults (Table 5.1).
test::Mdof2Values truth() {
  test::Mdof2Values v;
  v.m1 = 1.45, v.m2 = 1.02, v.k11 = 1.30e6, v.k22 = 0.255e6, v.k12 = 0.11e6, v.c11 = 14.2, v.c22 = 0.51;
  return v;
}

std::vector<double> truth_vector(const test::Mdof2Values& v) { return {v.m1, v.m2, v.k11, v.k22, v.k12, v.c11, v.c22}; }

double worst_relative_error(const FitResult& r, const test::Mdof2Values& v) {
  const std::vector<double> t = truth_vector(v);
  double worst = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    INFO(r.parameters[i].name << " = " << r.parameters[i].value << ", truth " << t[i]);
    CHECK(r.parameters[i].identifiable);
    worst = std::max(worst, std::abs(r.parameters[i].value - t[i]) / t[i]);
  }
  return worst;
}

FrfData noiseless_frf(const test::Mdof2Values& v) {
  std::mt19937 rng(1);
  return test::mdof2_frf_data(v, Eigen::VectorXd::LinSpaced(1561, 10, 400), 0.0, rng);
}

nlohmann::json details(const FitResult& r, const std::string& name) {
  return nlohmann::json::parse(r.method_details.at("two_step")).at(name);
}

}  // namespace

TEST_CASE("two-step from noiseless FRFs recovers the parameters exactly", "[two-step][frf]") {
  const test::LinearModel model = test::mdof2_model({}, true);
  const FitResult r = fit_two_step(model, {noiseless_frf(truth())});
  CHECK(r.method == "two-step");
  CHECK(worst_relative_error(r, truth()) < 1e-8);
  const nlohmann::json two = details(r, "step_two");
  // 4 denominator coefficients, 3 of d1/F1, 1 of d2/F1 (its s term c12/(m1 m2) is structurally zero: c12 fixed at 0).
  CHECK(two["equations"] == 8);
  CHECK(two["unknowns"] == 7);
  CHECK(two["solver"] == "minimisation");
  CHECK(two["newton"]["applicable"] == false);
  CHECK(two["minimisation"]["starts_at_best"] == 16);
  CHECK(two["q_tf"].get<double>() < 1e-18);
  // The step-one covariance propagates: noiseless data give (near) zero std.
  for (const ParameterEstimate& e : r.parameters) CHECK(e.std < 1e-6 * std::abs(e.value));
  // Identified and model poles coincide; every check passes.
  const nlohmann::json zero_pole = details(r, "zero_pole");
  for (const auto& p : zero_pole[0]["poles"]) CHECK(p["relative_distance"].get<double>() < 1e-9);
  CHECK(details(r, "checks")["verdict"].get<std::string>().rfind("valid", 0) == 0);
  CHECK(r.nrmse < 1e-8);
}

TEST_CASE("two-step on a square coefficient system solves it by Newton's method", "[two-step][frf][newton]") {
  // d2/F1 alone with the masses known: a_0 .. a_3 and b_0 = k12/(m1 m2), five equations in the five stiffnesses and
  // dampings.
  const test::Mdof2Values v = truth();
  FrfData d = noiseless_frf(v);
  d.channels.erase(d.channels.begin());
  const test::LinearModel model = test::mdof2_model({}, true);
  FitOptions options;
  options.values = {{"m1", v.m1}, {"m2", v.m2}};
  options.estimate = {"k11", "k22", "k12", "c11", "c22"};
  const FitResult r = fit_two_step(model, {d}, options);
  const nlohmann::json two = details(r, "step_two");
  CHECK(two["equations"] == 5);
  CHECK(two["unknowns"] == 5);
  CHECK(two["solver"] == "newton");
  REQUIRE(two["newton"]["applicable"] == true);
  const std::vector<double> t = {v.k11, v.k22, v.k12, v.c11, v.c22};
  for (std::size_t i = 0; i < t.size(); ++i) {
    INFO(r.parameters[i].name << " = " << r.parameters[i].value << ", truth " << t[i]);
    CHECK(std::abs(r.parameters[i].value - t[i]) < 1e-8 * t[i]);
  }
  // The truth is an admissible root (the equations are polynomial and may have others: the thesis's multiple
  // solutions; they are all listed).
  int admissible = 0;
  for (const auto& s : two["newton"]["solutions"]) admissible += s["admissible"].get<bool>();
  CHECK(admissible >= 1);

  TwoStepOptions minimise;
  minimise.solver = "minimisation";
  const FitResult m = fit_two_step(model, {d}, options, minimise);
  CHECK(details(m, "step_two")["solver"] == "minimisation");
  for (std::size_t i = 0; i < t.size(); ++i) CHECK(std::abs(m.parameters[i].value - t[i]) < 1e-8 * t[i]);
}

TEST_CASE("two-step from a noiseless record recovers the parameters", "[two-step][time]") {
  std::mt19937 rng(5);
  const test::Mdof2Values v = truth();
  const TimeRecord rec = test::mdof2_time_record(v, 8192, 1.0 / 4096, 0.0, rng);
  const test::LinearModel model = test::mdof2_model({}, true);
  // ARMAX (the default): the prediction errors of the exact record vanish at the truth (measured 6e-9).
  const FitResult r = fit_two_step(model, {rec});
  CHECK(worst_relative_error(r, v) < 1e-6);
  const nlohmann::json one = details(r, "step_one")[0];
  CHECK(one["source"] == "armax");
  CHECK(one["order"] == 4);
  int kept = 0;
  for (const auto& p : one["armax"]["poles"]) kept += p["kept"].get<bool>();
  CHECK(kept == 2);
  for (const ParameterEstimate& e : r.parameters) CHECK(std::isfinite(e.std));
  // ARX: a regression of a record sampled 25 times above its highest mode loses digits (its poles crowd z = 1).
  TwoStepOptions arx;
  arx.model = "arx";
  const FitResult a = fit_two_step(model, {rec}, {}, arx);
  CHECK(worst_relative_error(a, v) < 1e-5);
  CHECK(details(a, "step_one")[0]["source"] == "arx");
  // No covariance from ARX: std null, and the reason is given.
  for (const ParameterEstimate& e : a.parameters) CHECK(std::isnan(e.std));
  // The covariance keeps the size of `estimated` (reports index it so), all unknown.
  REQUIRE(a.covariance.rows() == static_cast<Eigen::Index>(a.estimated.size()));
  CHECK(a.correlation.rows() == static_cast<Eigen::Index>(a.estimated.size()));
  CHECK(a.covariance.array().isNaN().all());
  CHECK(details(a, "step_two")["uncertainty"].get<std::string>().rfind("std null", 0) == 0);
}

TEST_CASE("two-step refuses what it cannot use", "[two-step][errors]") {
  const test::LinearModel model = test::mdof2_model({}, true);
  const FrfData d = noiseless_frf(truth());
  TwoStepOptions bad;
  bad.solver = "bisection";
  CHECK_THROWS_WITH(fit_two_step(model, {d}, {}, bad), Catch::Contains("unknown solver bisection"));
  TwoStepOptions newton;
  newton.solver = "newton";
  CHECK_THROWS_WITH(fit_two_step(model, {d}, {}, newton), Catch::Contains("needs as many compared coefficients"));
  // A record far too short for a model of the model's order.
  std::mt19937 rng(2);
  const TimeRecord rec = test::mdof2_time_record(truth(), 40, 1.0 / 4096, 0.0, rng);
  CHECK_THROWS_WITH(fit_two_step(model, {rec}), Catch::Contains("too few for an ARMAX model of order 4"));
  CHECK_THROWS_AS(fit_two_step(model, {rec}), FitError);
  TwoStepOptions arx;
  arx.model = "arx";
  CHECK_THROWS_WITH(fit_two_step(model, {rec}, {}, arx), Catch::Contains("too few for an ARX model of order 4"));
  TwoStepOptions unknown;
  unknown.model = "oe";
  CHECK_THROWS_WITH(fit_two_step(model, {d}, {}, unknown), Catch::Contains("unknown model oe"));
}

TEST_CASE("two-step on noisy FRFs: the normalised weighting's error and the covariance weighting's", "[two-step][frf][noise]") {
  // 40 dB SNR (noise 1 % of each channel's RMS |H|), closed-form data. The thesis's normalised coefficient mismatch
  // lets the mass-2 group (m2, k22, k12) move by several per cent (the 0.05 % damped 90 Hz mode's coefficients are
  // weighted like the others); whitening by step one's covariance (the Markov estimate) reaches output-error accuracy.
  // Both report a std that covers their error: the propagation of step one's covariance.
  const test::LinearModel model = test::mdof2_model({}, true);
  const std::vector<double> t = truth_vector(truth());
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::mt19937 rng(seed);
    const FrfData d = test::mdof2_frf_data(truth(), Eigen::VectorXd::LinSpaced(1561, 10, 400), 0.01, rng);
    double rms[2] = {0, 0};
    for (int w = 0; w < 2; ++w) {
      TwoStepOptions o;
      o.weighting = w ? "covariance" : "normalised";
      const FitResult r = fit_two_step(model, {d}, {}, o);
      for (std::size_t i = 0; i < t.size(); ++i) {
        const ParameterEstimate& e = r.parameters[i];
        INFO("seed " << seed << ", " << o.weighting << ": " << e.name << " = " << e.value << " +- " << e.std << ", truth " << t[i]);
        CHECK(std::abs(e.value - t[i]) < 4 * e.std);
        rms[w] += std::pow((e.value - t[i]) / t[i], 2);
      }
      if (w) CHECK(r.nrmse < 0.011);  // the noise level: as good a fit as output error's
    }
    INFO("seed " << seed << ": RMS relative error normalised " << std::sqrt(rms[0] / 7) << ", covariance " << std::sqrt(rms[1] / 7));
    CHECK(std::sqrt(rms[1] / 7) < 0.005);
    CHECK(rms[1] < rms[0]);
  }
  TwoStepOptions bad;
  bad.weighting = "covariance";
  bad.model = "arx";
  std::mt19937 rng(4);
  CHECK_THROWS_WITH(fit_two_step(model, {test::mdof2_time_record(truth(), 8192, 1.0 / 4096, 0.01, rng)}, {}, bad),
                    Catch::Contains("covariance weighting needs step one's coefficient covariance"));
}

TEST_CASE("two-step from noisy records by ARMAX: the std covers the error, and the covariance weighting",
          "[two-step][time][noise][armax]") {
  // 40 dB output noise on an exact zero-order-hold record (2 s at 4096 Hz). ARMAX's coefficient covariance, propagated
  // through step two, covers the error; whitening by it (the Markov estimate) reaches output error's accuracy where
  // the thesis's normalised form leaves per cents.
  const test::LinearModel model = test::mdof2_model({}, true);
  const std::vector<double> t = truth_vector(truth());
  for (unsigned seed = 1; seed <= 2; ++seed) {
    std::mt19937 rng(10 + seed);
    const TimeRecord rec = test::mdof2_time_record(truth(), 8192, 1.0 / 4096, 0.01, rng);
    double rms[2] = {0, 0};
    for (int w = 0; w < 2; ++w) {
      TwoStepOptions o;
      o.weighting = w ? "covariance" : "normalised";
      const FitResult r = fit_two_step(model, {rec}, {}, o);
      for (std::size_t i = 0; i < t.size(); ++i) {
        const ParameterEstimate& e = r.parameters[i];
        INFO("seed " << seed << ", " << o.weighting << ": " << e.name << " = " << e.value << " +- " << e.std << ", truth " << t[i]);
        CHECK(std::abs(e.value - t[i]) < 4 * e.std);
        rms[w] += std::pow((e.value - t[i]) / t[i], 2);
      }
    }
    INFO("seed " << seed << ": RMS relative error normalised " << std::sqrt(rms[0] / 7) << ", covariance " << std::sqrt(rms[1] / 7));
    // Measured: normalised 3.4-4.4 %, covariance 0.05-0.09 % (output error's accuracy).
    CHECK(std::sqrt(rms[1] / 7) < 0.003);
    CHECK(rms[1] < rms[0]);
  }
}

namespace {

// The exact response from rest of M q'' + C q' + K q = B u, y = q, to u(t) = sum_j a_j cos(w_j t + phi_j) (a
// band-limited input, the case `# hold=none` describes), by modal superposition: z_k' = l_k z_k + b_k u, z_k(0) = 0.
TimeRecord sine_record(const test::Mdof2Values& v, double fs, Eigen::Index samples, std::mt19937& rng) {
  Eigen::MatrixXd M(2, 2), C(2, 2), K(2, 2);
  M << v.m1, 0, 0, v.m2;
  C << v.c11 + v.c12, -v.c12, -v.c12, v.c22 + v.c12;
  K << v.k11 + v.k12, -v.k12, -v.k12, v.k22 + v.k12;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
  A.topRightCorner(2, 2).setIdentity();
  A.bottomLeftCorner(2, 2) = -M.inverse() * K;
  A.bottomRightCorner(2, 2) = -M.inverse() * C;
  Eigen::VectorXd Bs = Eigen::VectorXd::Zero(4);
  Bs.tail(2) = M.inverse().col(0);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  const Eigen::VectorXcd l = es.eigenvalues();
  const Eigen::MatrixXcd V = es.eigenvectors();
  const Eigen::VectorXcd b = V.inverse() * Bs.cast<std::complex<double>>();
  std::uniform_real_distribution<double> unit(0, 1);
  struct Sine {
    double a, w, phi;
  };
  std::vector<Sine> sines;
  for (int j = 0; j < 40; ++j) sines.push_back({10 * unit(rng), 2 * M_PI * (20 + 180 * unit(rng)), 2 * M_PI * unit(rng)});
  TimeRecord r;
  r.file = "mdof2-sines.csv";
  r.hold = HoldMode::None;
  r.t = Eigen::VectorXd::LinSpaced(samples, 0, double(samples - 1) / fs);
  Eigen::VectorXd u(samples), y1(samples), y2(samples);
  const std::complex<double> i(0, 1);
  for (Eigen::Index n = 0; n < samples; ++n) {
    const double t = r.t[n];
    u[n] = 0;
    Eigen::VectorXcd z = Eigen::VectorXcd::Zero(4);
    for (const Sine& s : sines) {
      u[n] += s.a * std::cos(s.w * t + s.phi);
      for (int k = 0; k < 4; ++k) {
        const std::complex<double> decay = std::exp(l[k] * t);
        z[k] += b[k] * s.a / 2.0 *
                (std::exp(i * s.phi) * (std::exp(i * s.w * t) - decay) / (i * s.w - l[k]) +
                 std::exp(-i * s.phi) * (std::exp(-i * s.w * t) - decay) / (-i * s.w - l[k]));
      }
    }
    const Eigen::VectorXcd x = V * z;
    y1[n] = x[0].real();
    y2[n] = x[1].real();
  }
  r.signals = {{"F1", u}, {"d1", y1}, {"d2", y2}};
  return r;
}

}  // namespace

TEST_CASE("two-step from a record without hold (# hold=none) maps the ARX model under a first-order hold",
          "[two-step][time][hold]") {
  // A band-limited input (40 sines, 20-200 Hz) sampled at 8192 Hz, noiseless: linear interpolation between samples
  // (first-order hold) is close to it, a zero-order hold is half a sample late. The same samples read as held give a
  // worse continuous-time model.
  std::mt19937 rng(7);
  const test::Mdof2Values v = truth();
  TimeRecord rec = sine_record(v, 8192, 8192, rng);
  const test::LinearModel model = test::mdof2_model({}, true);
  // ARX: without noise, the interpolation's error (coloured, correlated with the input) is all the equation error;
  // ARMAX's free noise model then weights the fit where that error is small, and its poles go wrong (docs: limits).
  TwoStepOptions arx;
  arx.model = "arx";
  const FitResult none = fit_two_step(model, {rec}, {}, arx);
  CHECK(details(none, "step_one")[0]["arx"]["hold"] == "none (first-order hold)");
  const double err_none = worst_relative_error(none, v);
  rec.hold = HoldMode::ZeroOrder;
  const FitResult held = fit_two_step(model, {rec}, {}, arx);
  double err_held = 0;  // (read as held, c22 may end at its bound 0: no identifiable check here)
  for (std::size_t k = 0; k < 7; ++k)
    err_held = std::max(err_held, std::abs(held.parameters[k].value - truth_vector(v)[k]) / truth_vector(v)[k]);
  INFO("worst relative error with the record's hold " << err_none << ", read as zero-order hold " << err_held);
  // Linear interpolation is itself an approximation of the band-limited input (its error grows as (w dt)^2).
  CHECK(err_none < 5e-3);
  CHECK(err_held > 3 * err_none);
}

TEST_CASE("two-step from a noisy record without hold: ARMAX where ARX shows no mode", "[two-step][time][hold][armax]") {
  // The band-limited record above with 40 dB noise on the outputs: the long ARX's poles are then not significant
  // (refused), ARMAX (the default) reaches every parameter within 7 % (measured 2.7-5.7 % on three noise seeds).
  std::mt19937 rng(7);
  const test::Mdof2Values v = truth();
  TimeRecord rec = sine_record(v, 8192, 8192, rng);
  std::mt19937 noise(1);
  std::normal_distribution<double> gauss(0, 1);
  for (Signal& s : rec.signals)
    if (s.name != "F1") {
      const double rms = std::sqrt(s.values.squaredNorm() / double(s.values.size()));
      for (Eigen::Index k = 0; k < s.values.size(); ++k) s.values[k] += 0.01 * rms * gauss(noise);
    }
  const test::LinearModel model = test::mdof2_model({}, true);
  const FitResult r = fit_two_step(model, {rec});
  CHECK(details(r, "step_one")[0]["armax"]["hold"] == "none (first-order hold)");
  CHECK(worst_relative_error(r, v) < 0.07);
  TwoStepOptions arx;
  arx.model = "arx";
  CHECK_THROWS_WITH(fit_two_step(model, {rec}, {}, arx), Catch::Contains("shows no vibration mode significantly"));
}
