// A bug (a std::logic_error: out_of_range from .at(), a broken precondition) is not bad input: the estimators let it
// through to the command's internal-error status (docs/cli.md, status 3), where their handlers for failed trial
// points or data that cannot serve used to take it for a failed step or report it as bad input (status 1).
#include "mbgen_test/estimation.hpp"

#include "arx.hpp"
#include "model_coefficients.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"
#include "mbgen/methods/modal_fit.hpp"
#include "mbgen/methods/two_step.hpp"

#include <catch2/catch.hpp>

#include <random>
#include <stdexcept>

using namespace mbgen;

namespace {

// mdof2 whose evaluation has a bug away from its default values: an index out of range, as .at() would throw.
class BuggyModel : public Model {
 public:
  BuggyModel() : inner_(test::mdof2_model({}, true)) {}
  const ModelInfo& info() const override { return inner_.info(); }
  void evaluate(const Eigen::VectorXd& p, ModelMatrices& out) const override {
    if (p != info().default_values()) throw std::out_of_range("vector::_M_range_check: __n (which is 9) >= 8");
    inner_.evaluate(p, out);
  }
  void derivatives(const Eigen::VectorXd& p, ModelDerivatives& out) const override { inner_.derivatives(p, out); }

 private:
  test::Mdof2Model inner_;
};

std::vector<DataSet> frf_data() {
  test::Mdof2Values truth;
  truth.m1 *= 1.05;
  truth.k22 *= 0.95;
  std::mt19937 rng(7);
  return {test::mdof2_frf_data(truth, Eigen::VectorXd::LinSpaced(781, 10, 400), 0.0, rng)};
}

}  // namespace

TEST_CASE("a bug in the model's evaluation reaches the caller from every estimator", "[errors]") {
  const BuggyModel model;
  FitOptions options;
  options.starts = 2;
  // Output error: the trial steps' handler took it for a failed step (the fit ended at the prior, status 0).
  CHECK_THROWS_AS(fit(model, frf_data(), options), std::out_of_range);
  // Two-step: step one reported it as bad input (FitError); the searches took it for failed trials.
  CHECK_THROWS_AS(fit_two_step(model, frf_data(), options), std::out_of_range);
  // Modal: the comparison at trial points took it for a model without modes there.
  CHECK_THROWS_AS(fit_modal(model, frf_data(), options), std::out_of_range);
}

TEST_CASE("a broken precondition is a logic_error, not the invalid_argument of data that cannot serve", "[errors]") {
  // identify_arx's callers turn invalid_argument into "the record is too short" (status 1).
  const Eigen::VectorXd u = Eigen::VectorXd::Ones(100);
  bool logic = false, bad_input = false;
  try {
    methods::identify_arx(u, {u}, {"y"}, "u", 1e-3, false, 3, {1});  // an odd order
  } catch (const std::invalid_argument&) {
    bad_input = true;
  } catch (const std::logic_error&) {
    logic = true;
  }
  CHECK(logic);
  CHECK_FALSE(bad_input);
}

TEST_CASE("a model with fewer modes than the data at a trial point is a failed evaluation there", "[errors]") {
  // It was a std::domain_error (a logic_error): the searches now let those through as bugs.
  const test::Mdof2Model model = test::mdof2_model();
  const std::vector<std::complex<double>> three_modes = {{-1, 500}, {-1, 900}, {-1, 1500}};
  CHECK_THROWS_AS(methods::model_tf_truncated(model, model.info().default_values(), 0, {0, 1}, three_modes, {}),
                  DynamicsError);
}
