// Fits of the committed example data (examples/*/data, made by scripts/truthgen: an independent numpy assembly
// of the truth model, truth parameters 3-10 % off nominal, 40 dB SNR, coherence column), starting from the
// models' default values as in `mbgen fit examples/mdof2/mdof2.mdl --data examples/mdof2/data/frf_F1.csv`.
// The model is written by hand here (the runtime does not link the compiler), with the .mdl's values and bounds.
#include "mbgen_test/estimation.hpp"
#include "mbgen_test/example_data.hpp"

#include "mbgen/data/data_set.hpp"
#include "mbgen/estimation/fit.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mbgen;
using test::LinearModel;

using test::example_data;

TEST_CASE("slow: mdof2 FRF example: the global fit from the model's defaults reaches the truth", "[fit][frf][examples]") {
  const LinearModel model = test::mdof2_model({}, true);  // the .mdl's defaults and bounds
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
