// The model against output-only modes (mbgen/methods/operational_update.hpp): the weighted modal residuals and
// their Jacobian on mdof2 written by hand (test::Mdof2Model), checked against the undamped eigenproblem solved here
// and its eigenvalue derivatives; the update on noise-free modes of that eigenproblem; the update on truthgen's
// output-only records of drawn truths (numpy, its own simulation), with the refusal of the common factor.
#include "mbgen_test/mdof2.hpp"

#include "modal_identification/oma_truth.hpp"
#include "modal_solve.hpp"

#include "mbgen/methods/operational_update.hpp"
#include "mbgen/modal_identification/operational_comparison.hpp"

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <complex>
#include <fstream>
#include <map>
#include <string>

using namespace mbgen;

namespace {

const double kTwoPi = 2 * std::acos(-1.0);

// The undamped mdof2's eigenpairs: K phi = lambda M phi, lambda = (2 pi f)^2, ascending.
struct Eigenpairs {
  Eigen::Matrix2d M, K;
  Eigen::Vector2d lambda;
  Eigen::Matrix2d phi;
};
Eigenpairs undamped(const test::Mdof2Values& v) {
  Eigenpairs e;
  e.M << v.m1, 0, 0, v.m2;
  e.K << v.k11 + v.k12, -v.k12, -v.k12, v.k22 + v.k12;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> s(e.K, e.M);
  e.lambda = s.eigenvalues();
  e.phi = s.eigenvectors();
  return e;
}

test::Mdof2Values undamped_values(test::Mdof2Values v) {
  v.c11 = v.c22 = v.c12 = 0;
  return v;
}

double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  return std::norm(a.dot(b)) / (a.squaredNorm() * b.squaredNorm());
}

// The weighted residuals of `targets` at p, paired by MAC (what the update minimizes).
methods::ParameterObjectives objectives_of(const Model& model, const std::vector<OperationalTarget>& targets) {
  return [&model, &targets](const Eigen::VectorXd& p, Eigen::VectorXd& r) {
    const OperationalModelModes mm = operational_model_modes(model, p, {0, 1});
    const std::vector<int> pairing = pair_by_mac(targets, mm);
    const int per = operational_residuals_per_mode(2);
    r.resize(per * static_cast<Eigen::Index>(targets.size()));
    for (std::size_t t = 0; t < targets.size(); ++t) {
      const auto m = static_cast<std::size_t>(pairing[t]);
      operational_residuals(targets[t], mm.f_hz[m], mm.shapes[m], r.segment(per * static_cast<Eigen::Index>(t), per));
    }
    return true;
  };
}

}  // namespace

TEST_CASE("operational residuals: frequency and shape after the best complex factor, weighted",
          "[operational_update]") {
  const test::Mdof2Values v = undamped_values({});
  const test::Mdof2Model model = test::mdof2_model(v);
  const Eigenpairs e = undamped(v);
  const OperationalModelModes mm = operational_model_modes(model, model.info().default_values(), {0, 1});
  REQUIRE(mm.f_hz.size() == 2);
  for (int k = 0; k < 2; ++k) {
    CHECK(mm.f_hz[static_cast<std::size_t>(k)] == Approx(std::sqrt(e.lambda[k]) / kTwoPi).epsilon(1e-10));
    CHECK(mac(mm.shapes[static_cast<std::size_t>(k)], e.phi.col(k).cast<std::complex<double>>()) ==
          Approx(1).epsilon(1e-12));
  }
  // A target 0.01 Hz above mode 1, its shape turned a little and by an arbitrary phase.
  OperationalTarget t;
  t.f_hz = mm.f_hz[0] + 0.01;
  t.f_std_hz = 0.005;
  t.shape_std = 1e-3;
  Eigen::VectorXcd shape = e.phi.col(0).cast<std::complex<double>>() +
                           Eigen::Vector2cd(std::complex<double>(0, 0), std::complex<double>(0.1, 0.05));
  shape *= std::polar(1.0 / shape.norm(), 0.3);
  t.shape = shape;
  Eigen::VectorXd r(operational_residuals_per_mode(2));
  operational_residuals(t, mm.f_hz[0], mm.shapes[0], r);
  CHECK(r[0] == Approx(-2).epsilon(1e-9));
  const double one_minus_mac = 1 - mac(shape, e.phi.col(0).cast<std::complex<double>>());
  CHECK(one_minus_mac > 1e-4);
  CHECK(r.tail(4).squaredNorm() == Approx(one_minus_mac / (t.shape_std * t.shape_std)).epsilon(1e-9));
  // Unscaled shapes: the model shape's size and phase do not matter.
  Eigen::VectorXd r2(operational_residuals_per_mode(2));
  operational_residuals(t, mm.f_hz[0], mm.shapes[0] * std::complex<double>(2, -3), r2);
  CHECK((r2 - r).norm() < 1e-12 * r.norm());
  // Pairing by MAC whatever the order of the targets.
  OperationalTarget other = t;
  other.shape = e.phi.col(1).cast<std::complex<double>>();
  const std::vector<int> pairing = pair_by_mac({other, t}, mm);
  CHECK(pairing == std::vector<int>{1, 0});
}

TEST_CASE("operational residuals: the Jacobian in log parameters against the eigenvalue derivatives",
          "[operational_update]") {
  const test::Mdof2Values v = undamped_values({});
  const test::Mdof2Model model = test::mdof2_model(v);
  const Eigenpairs e = undamped(v);
  std::vector<OperationalTarget> targets(2);
  for (int k = 0; k < 2; ++k) {
    OperationalTarget& t = targets[static_cast<std::size_t>(k)];
    t.f_hz = 1.01 * std::sqrt(e.lambda[k]) / kTwoPi;
    t.shape = e.phi.col(k).cast<std::complex<double>>().normalized();
    t.f_std_hz = 0.02;
    t.shape_std = 1e-3;
  }
  const Eigen::VectorXd p = model.info().default_values();
  const std::vector<int> which{0, 1, 2, 3, 4};  // m1, m2, k11, k22, k12
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  REQUIRE(methods::log_scale_jacobian(model.info(), objectives_of(model, targets), p, which, r, J));
  // d lambda / d p_j = phi^T (dK_j - lambda dM_j) phi / (phi^T M phi); f = sqrt(lambda) / 2 pi.
  std::vector<Eigen::Matrix2d> dM(5, Eigen::Matrix2d::Zero()), dK(5, Eigen::Matrix2d::Zero());
  dM[0](0, 0) = 1;
  dM[1](1, 1) = 1;
  dK[2](0, 0) = 1;
  dK[3](1, 1) = 1;
  dK[4] << 1, -1, -1, 1;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d phi = e.phi.col(k);
    const double lambda = e.lambda[k];
    const int row = k * operational_residuals_per_mode(2);
    for (int j = 0; j < 5; ++j) {
      const double dl = phi.dot((dK[static_cast<std::size_t>(j)] - lambda * dM[static_cast<std::size_t>(j)]) * phi) /
                        phi.dot(e.M * phi);
      const double expected =
          p[j] * dl / (2 * kTwoPi * std::sqrt(lambda)) / targets[static_cast<std::size_t>(k)].f_std_hz;
      CHECK(J(row, j) == Approx(expected).epsilon(1e-5).margin(1e-6 * J.row(row).cwiseAbs().maxCoeff()));
    }
    // The common factor of masses and stiffnesses changes neither the frequency nor the shape.
    CHECK(J.row(row).sum() == Approx(0).margin(1e-5 * J.row(row).cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("operational update: noise-free modes of a truth, one mass known", "[operational_update]") {
  test::Mdof2Values truth = undamped_values({});
  truth.m1 = 1.52;
  truth.m2 = 1.01;
  truth.k11 = 1.26e6;
  truth.k22 = 0.219e6;
  truth.k12 = 0.128e6;
  const Eigenpairs e = undamped(truth);
  std::vector<OperationalTarget> targets(2);
  for (int k = 0; k < 2; ++k) {
    OperationalTarget& t = targets[static_cast<std::size_t>(k)];
    t.f_hz = std::sqrt(e.lambda[k]) / kTwoPi;
    t.shape = e.phi.col(k).cast<std::complex<double>>().normalized();
    t.f_std_hz = 0.01;
    t.shape_std = 1e-3;
  }
  const test::Mdof2Model model = test::mdof2_model(undamped_values({}));  // the nominal values as priors
  FitOptions options;
  options.values["m1"] = truth.m1;
  options.estimate = {"m2", "k11", "k22", "k12"};
  const OperationalUpdate u = update_from_operational_modes(model, {"d1", "d2"}, targets, options);
  const std::map<std::string, double> expected{{"m2", truth.m2}, {"k11", truth.k11}, {"k22", truth.k22},
                                               {"k12", truth.k12}};
  REQUIRE(u.parameters.size() == 4);
  for (const UpdatedParameter& p : u.parameters) {
    INFO(p.name);
    CHECK(p.estimate == Approx(expected.at(p.name)).epsilon(1e-6));
    CHECK(p.std > 0);
  }
  CHECK(u.chi2_after < 1e-8);
  REQUIRE(u.pairs.size() == 2);
  CHECK(u.pairs[1].mac_after == Approx(1).epsilon(1e-10));

  // Every mass and stiffness estimated: refused, naming the fix.
  options.estimate = {"m1", "m2", "k11", "k22", "k12"};
  options.values.clear();
  CHECK_THROWS_WITH(update_from_operational_modes(model, {"d1", "d2"}, targets, options),
                    Catch::Contains("only up to a common factor") && Catch::Contains("--fix NAME"));
}

// truthgen --kind oma of mdof2 (40 dB, 300 s at 1024 Hz), drawn truths 1 and 2, m1 known at the truth, the nominal
// values as priors. Measured: masses and stiffnesses within 0.07 % (draw 1) and 0.18 % (draw 2) of the truth, 0.2 to
// 0.7 standard deviations; the dampings within 8 % (c11: 2.9 and 1.5 standard deviations) and 35 % (c22, the
// lightly damped mode's: 0.5 and 2.6). Asserted: masses and stiffnesses within 3 %, every estimate within 3
// standard deviations (issue 34's consistency target). The identified modes against the truth's, in their block
// standard deviations: frequencies 0.15 to 1.1, damping ratios 1.5 to 2.9 (SSI-cov's damping bias, which the blocks
// share, is not in their spread); asserted: 3.
TEST_CASE("operational update: truthgen's output-only records of drawn mdof2 truths", "[operational_update]") {
  for (const int draw : {1, 2}) {
    const int seed = 60 + draw;
    INFO("draw " << draw);
    test::OmaRecord record = test::oma_record("methods_operational_update", "mdof2", draw, seed);
    REQUIRE(record.modes.size() == 2);
    std::ifstream in(std::string(mbgen_binary_dir()) + "/methods_operational_update/mdof2_draw" +
                     std::to_string(draw) + "_seed" + std::to_string(seed) + ".truth.json");
    const nlohmann::json truth = nlohmann::json::parse(in).at("parameters");
    const ResponseData data = response_data({record.record});
    const OutputOnlyOptions oma;
    const OutputOnlyIdentification id = identify_output_only(data, oma);
    REQUIRE(id.modes.size() == 2);
    const BlockUncertainty unc = block_uncertainty(data, id, oma);
    std::vector<OperationalTarget> targets;
    for (std::size_t m = 0; m < id.modes.size(); ++m) {
      const ModeUncertainty& s = unc.modes[m];
      REQUIRE(s.blocks_found >= 6);
      // The block standard deviations against the truth's modes (numpy's eigenvalues, the .truth.json).
      const test::TruthMode& tm = record.modes[m];
      INFO("mode " << m << ": f " << id.modes[m].f_hz << " +- " << s.f_std_hz << " (truth " << tm.f_hz << "), zeta "
                   << id.modes[m].zeta << " +- " << s.zeta_std << " (truth " << tm.zeta << ")");
      CHECK(std::abs(id.modes[m].f_hz - tm.f_hz) < 3 * s.f_std_hz);
      CHECK(std::abs(id.modes[m].zeta - tm.zeta) < 3 * s.zeta_std);
      targets.push_back({id.modes[m].f_hz, id.modes[m].zeta, id.modes[m].shape, s.f_std_hz, s.zeta_std, s.shape_std});
    }
    const test::Mdof2Model model = test::mdof2_model();
    FitOptions options;
    options.values["m1"] = truth.at("m1").get<double>();
    options.estimate = {"m2", "k11", "k22", "k12", "c11", "c22"};
    const OperationalUpdate u = update_from_operational_modes(model, data.channels, targets, options);
    REQUIRE(u.parameters.size() == 6);
    for (const UpdatedParameter& p : u.parameters) {
      const double t = truth.at(p.name).get<double>();
      INFO(p.name << " = " << p.estimate << " +- " << p.std << ", truth " << t);
      if (p.kind == "mass/stiffness") CHECK(std::abs(p.estimate - t) < 0.03 * t);
      CHECK(std::abs(p.estimate - t) < 3 * p.std);
    }
    options.values.clear();
    options.estimate = {"m1", "m2", "k11", "k22", "k12", "c11", "c22"};
    CHECK_THROWS_WITH(update_from_operational_modes(model, data.channels, targets, options),
                      Catch::Contains("common factor") && Catch::Contains("--fix"));
  }
}
