// The records' H1 estimates against the model's exact FRF, on an mdof2 record simulated exactly in the test (modal
// zero-order-hold superposition, test_support): the plain H1 flattens the lightly damped second mode; with the
// estimator's bias at the parameters divided out, it is the exact FRF again.
#include "mbgen_test/estimation.hpp"

#include "mbgen/dynamics/frf.hpp"
#include "mbgen/estimation/spectral_companion.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mbgen;

namespace {

// The largest relative error |H1 - H| / |H| over the companion's lines and channels, H the model's exact FRF at p.
double worst_relative_error(const Model& model, const Eigen::VectorXd& p, const estimation::SpectralCompanion& c) {
  const FrfData& h1 = std::get<FrfData>(c.data.front().content);
  const std::vector<double> f(h1.f_hz.data(), h1.f_hz.data() + h1.f_hz.size());
  const FrfResult exact = frf(model, p, f);
  double worst = 0;
  for (const FrfChannel& ch : h1.channels) {
    const int o = model.info().output_index(ch.output), i = model.info().input_index(ch.input);
    for (Eigen::Index k = 0; k < ch.values.size(); ++k) {
      const std::complex<double> h = exact.H[static_cast<std::size_t>(k)](o, i);
      worst = std::max(worst, std::abs(ch.values[k] - h) / std::abs(h));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("the H1 companion with the estimator's bias divided out is the exact FRF", "[fit][time]") {
  const test::Mdof2Values truth;
  std::mt19937 rng(3);
  const TimeRecord record = test::mdof2_time_record(truth, 8000, 1.0 / 2000, 0.0, rng);
  const test::LinearModel model = test::mdof2_model(truth);
  const Eigen::VectorXd p = model.info().default_values();
  const std::vector<DataSet> data = {DataSet(record)};
  const Eigen::VectorXd lines = Eigen::VectorXd::LinSpaced(50, 20, 300);
  const FrfData measured_frf = test::mdof2_frf_data(truth, lines, 0.0, rng);
  const auto with_frf = estimation::debiased_spectral_companion(model, p, {DataSet(measured_frf), DataSet(record)});
  REQUIRE(with_frf);
  REQUIRE(with_frf->data.size() == 2);
  CHECK(std::get<FrfData>(with_frf->data[0].content).channels[0].values == measured_frf.channels[0].values);
  const auto plain = estimation::spectral_companion(model.info(), data);
  const auto debiased = estimation::debiased_spectral_companion(model, p, data);
  REQUIRE(plain);
  REQUIRE(debiased);
  CHECK(debiased->averages == plain->averages);
  const double plain_error = worst_relative_error(model, p, *plain);
  const double debiased_error = worst_relative_error(model, p, *debiased);
  INFO("plain H1: " << plain_error << ", bias divided out: " << debiased_error);
  CHECK(plain_error > 0.05);  // the flattened peak
  CHECK(debiased_error < 1e-3);
  // The ratio is taken where the model's modes are: at a model whose lightly damped second mode (0.05 % of
  // critical) lies half a line off, it moves the flattened peak rather than undoing it. A diagnosis takes it at the
  // current model's estimate, fitted to the records, whose modes are the data's to far better than a line.
  test::Mdof2Values off = truth;
  off.k22 *= 1.02;
  const test::LinearModel near = test::mdof2_model(off);
  const auto at_near = estimation::debiased_spectral_companion(near, near.info().default_values(), data);
  REQUIRE(at_near);
  CHECK(worst_relative_error(model, p, *at_near) > plain_error);
}
