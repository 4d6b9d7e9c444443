// The errors-in-variables problem (eiv_problem.hpp) on mdof2 records simulated here: the frequency-domain relation
// with its transient term is exact for a noise-free record (both holds, displacement, velocity and acceleration
// outputs); the Kaufman Jacobian gives the exact gradient of the projected cost (central differences); the noise
// levels come back from a record with known white force and output noise.
#include "eiv_problem.hpp"

#include "mbgen/dynamics/simulate.hpp"
#include "mbgen_test/finite_difference.hpp"
#include "mbgen_test/mdof2.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace mbgen;
using methods::EivNoise;
using methods::EivProblem;

namespace {

struct Record {
  TimeRecord record;
  Eigen::MatrixXd clean_outputs;
};

// mdof2 (outputs d1, d2, v1, a2) from rest, driven by a random binary force of +-10 N, 2048 samples at 2048 Hz; the
// written force and outputs with white noise of the given standard deviations (0: none).
Record make_record(const Model& model, HoldMode hold, double force_sigma, const Eigen::VectorXd& output_sigma,
                   unsigned seed) {
  const Eigen::Index n = 2048;
  const double dt = 1.0 / 2048;
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution coin;
  std::normal_distribution<double> normal;
  Eigen::MatrixXd u(n, 1);
  for (Eigen::Index k = 0; k < n; ++k) u(k, 0) = coin(rng) ? 10.0 : -10.0;
  Eigen::VectorXd p(static_cast<Eigen::Index>(model.info().parameters.size()));
  for (std::size_t i = 0; i < model.info().parameters.size(); ++i)
    p[static_cast<Eigen::Index>(i)] = model.info().parameters[i].value;
  const InputHold h = hold == HoldMode::None ? InputHold::FirstOrder : InputHold::ZeroOrder;
  const Eigen::MatrixXd y = simulate(model, p, u, dt, h);
  Record r;
  r.clean_outputs = y;
  r.record.file = "simulated";
  r.record.hold = hold;
  r.record.t = Eigen::VectorXd::LinSpaced(n, 0, double(n - 1) * dt);
  Eigen::VectorXd f = u.col(0);
  for (Eigen::Index k = 0; k < n; ++k) f[k] += force_sigma * normal(rng);
  r.record.signals.push_back({"F1", f});
  for (Eigen::Index o = 0; o < y.cols(); ++o) {
    Eigen::VectorXd v = y.col(o);
    for (Eigen::Index k = 0; k < n; ++k) v[k] += output_sigma[o] * normal(rng);
    r.record.signals.push_back({model.info().outputs[static_cast<std::size_t>(o)], v});
  }
  return r;
}

Eigen::VectorXd values_of(const Model& model) {
  Eigen::VectorXd p(static_cast<Eigen::Index>(model.info().parameters.size()));
  for (std::size_t i = 0; i < model.info().parameters.size(); ++i)
    p[static_cast<Eigen::Index>(i)] = model.info().parameters[i].value;
  return p;
}

const std::vector<int> kFree = {0, 1, 2, 3, 4, 5, 6};  // m1 .. c22

}  // namespace

TEST_CASE("eiv: a noise-free record meets the model's frequency-domain relation exactly, transient included") {
  const test::Mdof2Model model(true);
  const Eigen::VectorXd p = values_of(model);
  for (HoldMode hold : {HoldMode::ZeroOrder, HoldMode::None}) {
    const Record rec = make_record(model, hold, 0.0, Eigen::VectorXd::Zero(4), 1);
    const std::vector<DataSet> data = {DataSet(rec.record)};
    const EivProblem problem(model, data, kFree, p);
    const std::vector<EivNoise> noise = problem.initial_noise();
    Eigen::VectorXd r;
    REQUIRE(problem.evaluate(p, noise, r, nullptr));
    // The whitened data's size for comparison: the same residuals with the parameters 1 % off.
    Eigen::VectorXd off = p;
    off[2] *= 1.01;
    Eigen::VectorXd r_off;
    REQUIRE(problem.evaluate(off, noise, r_off, nullptr));
    INFO("hold " << (hold == HoldMode::None ? "none" : "zoh") << ": |r| " << r.norm() << ", 1 % off " << r_off.norm());
    CHECK(r.norm() < 1e-8 * r_off.norm());
  }
}

TEST_CASE("eiv: the Kaufman Jacobian gives the exact gradient of the projected cost") {
  const test::Mdof2Model model(true);
  const Eigen::VectorXd truth = values_of(model);
  const Record rec = make_record(model, HoldMode::ZeroOrder, 0.1, Eigen::VectorXd::Constant(4, 0.0), 2);
  // Output noise 1 % of each output's RMS.
  TimeRecord noisy = rec.record;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  for (std::size_t s = 1; s < noisy.signals.size(); ++s) {
    Eigen::VectorXd& v = noisy.signals[s].values;
    const double level = 0.01 * std::sqrt(v.squaredNorm() / double(v.size()));
    for (Eigen::Index k = 0; k < v.size(); ++k) v[k] += level * normal(rng);
  }
  const std::vector<DataSet> data = {DataSet(noisy)};
  const EivProblem problem(model, data, kFree, truth);
  std::vector<EivNoise> noise = problem.initial_noise();
  noise = problem.estimate_noise(truth, noise);
  Eigen::VectorXd p = truth;
  p[0] *= 1.002, p[3] *= 0.998, p[6] *= 1.01;  // away from the optimum: a gradient worth checking
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  REQUIRE(problem.evaluate(p, noise, r, &J));
  const Eigen::VectorXd gradient = J.transpose() * r;
  const auto half_cost = [&](const Eigen::VectorXd& q) -> Eigen::VectorXd {
    Eigen::VectorXd rq;
    REQUIRE(problem.evaluate(q, noise, rq, nullptr));
    return Eigen::VectorXd::Constant(1, 0.5 * rq.squaredNorm());
  };
  for (std::size_t j = 0; j < kFree.size(); ++j) {
    const double h = test::central_step(p[kFree[j]], 1e-6);
    const double numeric = test::central_difference(half_cost, p, kFree[j], h)[0];
    INFO(model.info().parameters[static_cast<std::size_t>(kFree[j])].name << ": analytic "
         << gradient[static_cast<Eigen::Index>(j)] << ", central difference " << numeric);
    CHECK(std::abs(gradient[static_cast<Eigen::Index>(j)] - numeric) <= 1e-4 * std::abs(numeric) + 1e-6 * gradient.norm());
  }
}

TEST_CASE("eiv: white force and output noise levels come back from the record's equation errors") {
  const test::Mdof2Model model(false);
  const Eigen::VectorXd truth = values_of(model);
  const Record clean = make_record(model, HoldMode::ZeroOrder, 0.0, Eigen::VectorXd::Zero(2), 4);
  Eigen::VectorXd output_sigma(2);
  for (Eigen::Index o = 0; o < 2; ++o)
    output_sigma[o] = 0.01 * std::sqrt(clean.clean_outputs.col(o).squaredNorm() / double(clean.clean_outputs.rows()));
  const double force_sigma = 10 * std::pow(10.0, -40 / 20.0);  // 40 dB
  const Record rec = make_record(model, HoldMode::ZeroOrder, force_sigma, output_sigma, 4);
  const std::vector<DataSet> data = {DataSet(rec.record)};
  const EivProblem problem(model, data, kFree, truth);
  std::vector<EivNoise> noise = problem.initial_noise();
  for (int i = 0; i < 3; ++i) noise = problem.estimate_noise(truth, noise);
  // 1023 lines: the output levels to a few per cent; the force's from the fewer lines near the resonances.
  INFO("force " << std::sqrt(noise[0].input[0]) << " of " << force_sigma << "; d1 " << std::sqrt(noise[0].output[0])
                << " of " << output_sigma[0] << "; d2 " << std::sqrt(noise[0].output[1]) << " of " << output_sigma[1]);
  CHECK(std::abs(std::sqrt(noise[0].input[0]) / force_sigma - 1) < 0.15);
  CHECK(std::abs(std::sqrt(noise[0].output[0]) / output_sigma[0] - 1) < 0.05);
  CHECK(std::abs(std::sqrt(noise[0].output[1]) / output_sigma[1] - 1) < 0.05);
}
