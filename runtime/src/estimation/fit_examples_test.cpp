// Fits of the committed example data (examples/*/data, made by scripts/truthgen: an independent numpy assembly
// of the truth model, truth parameters 3-10 % off nominal, 40 dB SNR, coherence column), starting from the
// models' default values as in `mbgen fit examples/mdof2/mdof2.mdl --data examples/mdof2/data/frf_F1.csv`.
// The model is written by hand here (the runtime does not link the compiler), with the .mdl's values and bounds.
#include "test_support.hpp"

#include "mbgen/data_set.hpp"
#include "mbgen/fit.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mbgen;
using test::LinearModel;

namespace {

// examples/mdof2/mdof2.mdl: defaults (thesis Table 5.1) and bounds.
LinearModel mdof2_as_in_model_file() {
  using R = ParameterRole;
  LinearModel m("mdof2", 2, {"F1"}, {"d1", "d2"});
  const int m1 = m.parameter("m1", 1.39, R::Estimate, 0, 100), m2 = m.parameter("m2", 1.09, R::Estimate, 0, 100);
  const int k11 = m.parameter("k11", 1.38e6, R::Estimate, 0, 1e9), k22 = m.parameter("k22", 0.24e6, R::Estimate, 0, 1e9);
  const int k12 = m.parameter("k12", 0.12e6, R::Estimate, 0, 1e9);
  const int c11 = m.parameter("c11", 13.42, R::Estimate, 0, 1e4), c22 = m.parameter("c22", 0.47, R::Estimate, 0, 1e4);
  const int c12 = m.parameter("c12", 0, R::Fixed);
  m.linear(LinearModel::M, m1, 0, 0, 1);
  m.linear(LinearModel::M, m2, 1, 1, 1);
  m.element(LinearModel::K, k11, 0, -1);
  m.element(LinearModel::K, k22, 1, -1);
  m.element(LinearModel::K, k12, 0, 1);
  m.element(LinearModel::C, c11, 0, -1);
  m.element(LinearModel::C, c22, 1, -1);
  m.element(LinearModel::C, c12, 0, 1);
  m.constant(LinearModel::B, 0, 0, 1);
  m.constant(LinearModel::Cd, 0, 0, 1);
  m.constant(LinearModel::Cd, 1, 1, 1);
  return m;
}

DataSet example_data(const std::string& relative) {
  const DataFile f = read_data_file(std::string(MBGEN_SOURCE_DIR) + "/" + relative);
  return std::visit([](const auto& d) { return DataSet(d); }, f);
}

}  // namespace

TEST_CASE("slow: mdof2 FRF example: the global fit from the model's defaults reaches the truth", "[fit][frf][examples]") {
  const LinearModel model = mdof2_as_in_model_file();
  // examples/mdof2/data/frf_F1.truth.json
  const std::vector<std::pair<std::string, double>> truth = {{"m1", 1.262},    {"m2", 1.022},   {"k11", 1300000.0},
                                                             {"k22", 259600.0}, {"k12", 109800.0}, {"c11", 14.39},
                                                             {"c22", 0.4906}};
  const FitResult r = fit(model, {example_data("examples/mdof2/data/frf_F1.csv")}, FitOptions{});
  INFO("nrmse " << r.nrmse << ", best start " << r.best_start);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const ParameterEstimate& e = r.parameters[i];
    REQUIRE(e.name == truth[i].first);
    INFO(e.name << " = " << e.value << " +- " << e.std << ", truth " << truth[i].second);
    CHECK(e.identifiable);
    CHECK(std::abs(e.value - truth[i].second) < 3 * e.std);
  }
  // 40 dB SNR: noise 1 % of the RMS |H|, so the relative residual is about 0.01.
  CHECK(r.nrmse < 0.013);
}
