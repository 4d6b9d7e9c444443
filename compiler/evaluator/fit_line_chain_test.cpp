// The chain of test_line_chain.hpp at 13 bodies (39 parameters, the structure of bench/fit_line_chain's 99-parameter
// chain): an FRF fit from the model file's defaults to a truth drawn within +-20 % of them, two draws. The data are
// the hand-assembled tridiagonal chain's accelerances (test_line_chain.hpp's Thomas solve, nothing of the compiler
// or the runtime) with 1 % complex noise proportional to |H|, whose coherence the data carry (the H1 variance of
// FrfWeighting then matches the noise, so the reported std are meant to hold).
//
// Beside the evaluator because it needs the model from its .mdl text (as fit_spindle_test.cpp).
#include "evaluator/symbolic_evaluator.hpp"
#include "evaluator/test_line_chain.hpp"
#include "frontend/parser.hpp"

#include "mbgen/estimation/fit.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mbgen;
namespace lc = mbgen::test::line_chain;

namespace {

constexpr int kBodies = 13, kEvery = 3;
constexpr double kSpread = 0.2;  // the truth within +-20 % of the model's defaults

}  // namespace

TEST_CASE("a 39-parameter chain along one axis is identifiable and fitted to the truth within the noise",
          "[fit][frf][chain]") {
  const auto model = evaluator::make_evaluator(frontend::parse_string(lc::model_text(kBodies, kEvery), "chain.mdl"));
  const ModelInfo& info = model->info();
  REQUIRE(info.parameters.size() == 3 * kBodies);
  REQUIRE(info.outputs.size() == 5);  // bodies 13, 10, 7, 4 and 1
  for (unsigned seed : {101u, 202u}) {
    // The modes lie between 11 and 230 Hz (damping ratios 0.5-10 %); the data's lines span 2..400 Hz.
    const lc::Draw c = lc::draw(info, kBodies, kEvery, seed, kSpread);
    double prior_error = 0;
    for (Eigen::Index i = 0; i < c.truth.size(); ++i)
      prior_error = std::max(prior_error, std::fabs(info.parameters[static_cast<std::size_t>(i)].value / c.truth[i] - 1));
    CHECK(prior_error > 0.15);  // the start is well away from the truth

    FitOptions options;
    // From the model's defaults and three starts within a factor 1.3 of them (log-ratio search, then refine): one
    // start alone ends in a local optimum (a missed mode) for about one draw in ten (seed 202 here; bench/README.md).
    options.starts = 4;
    options.spread = 1.3;
    options.search_cost_tolerance = 1e-4;   // the search only has to reach the basin (FitOptions)
    options.frf_weighting.floor = 1e-9;     // relative noise down to the anti-resonances: no floor needed
    const FitResult r = fit(*model, {DataSet(c.data)}, options);
    INFO("seed " << seed << ": nrmse " << r.nrmse << ", " << r.stop_reason);

    // The runtime's identifiability analysis (fit.cpp: at the prior and at the estimate) keeps every parameter,
    // and the unit-column Jacobian is far from the rank tolerance (1e-7): the ratio is about 1e-2 here.
    CHECK(r.estimated.size() == info.parameters.size());
    REQUIRE(r.singular_values.size() == static_cast<Eigen::Index>(info.parameters.size()));
    CHECK(r.singular_values.tail(1)[0] / r.singular_values[0] > 1e-4);
    // The residual is the noise: nrmse = 1 % (the noise is 1 % of |H| at every line).
    CHECK(r.nrmse == Approx(lc::kNoise).epsilon(0.05));

    double worst_mk = 0, worst_c = 0, sum_z2 = 0;
    for (const ParameterEstimate& p : r.parameters) {
      const double t = c.truth[info.parameter_index(p.name)];
      INFO(p.name << ": truth " << t << ", estimate " << p.value << " +- " << p.std);
      REQUIRE(p.identifiable);
      REQUIRE(p.std > 0);
      const double z = (p.value - t) / p.std;
      CHECK(std::fabs(z) < 4.0);  // 39 draws of a standard normal: |z| >= 4 has probability 0.25 %
      sum_z2 += z * z;
      double& worst = p.name[0] == 'c' ? worst_c : worst_mk;
      worst = std::max(worst, std::fabs(p.value / t - 1));
    }
    // The std are honest on average (RMS z about 1; the 39 z are correlated, so it scatters more than 1 +- 0.11;
    // 0.67 and 1.29 here), the masses and stiffnesses are determined to about 1 % and the dampers to a few.
    const double rms_z = std::sqrt(sum_z2 / double(r.parameters.size()));
    INFO("RMS z " << rms_z << ", largest relative error: masses and stiffnesses " << worst_mk << ", dampers " << worst_c);
    CHECK(rms_z > 0.4);
    CHECK(rms_z < 1.5);
    CHECK(worst_mk < 0.03);
    CHECK(worst_c < 0.1);
  }
}
