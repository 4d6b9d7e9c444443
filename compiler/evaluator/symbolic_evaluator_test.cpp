#include "mbgen_test/files.hpp"
#include "evaluator/symbolic_evaluator.hpp"

#include <catch2/catch.hpp>

#include <random>

#include <mbgen/dynamics/frf.hpp>

#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"

using namespace mbgen;

namespace {

// Parameter values spread around the defaults, reproducibly.
Eigen::VectorXd random_values(const ModelInfo& info, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> factor(0.5, 1.5);
  Eigen::VectorXd p = info.default_values();
  for (Eigen::Index i = 0; i < p.size(); ++i) p[i] = p[i] == 0 ? factor(rng) - 0.5 : p[i] * factor(rng);
  return p;
}

double evalf_at(const GiNaC::ex& e, const symbolic::SymbolicModel& sym, const Eigen::VectorXd& p) {
  GiNaC::exmap values;
  for (std::size_t i = 0; i < sym.parameters.size(); ++i)
    values[sym.parameters[i].sym] = GiNaC::numeric(p[static_cast<Eigen::Index>(i)]);
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(values).evalf()).to_double();
}

void check_against_ginac(const std::string& file) {
  const ir::ModelIr model = frontend::parse_file(file);
  symbolic::DeriveOptions o;
  o.transfer_functions = false;
  const symbolic::SymbolicModel sym = symbolic::derive(model, o);
  const evaluator::SymbolicEvaluator eval(sym);
  REQUIRE(eval.info().parameters.size() == sym.parameters.size());
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const Eigen::VectorXd p = random_values(eval.info(), seed);
    ModelMatrices mm;
    eval.evaluate(p, mm);
    const std::pair<const GiNaC::matrix*, const Eigen::MatrixXd*> pairs[] = {
        {&sym.M, &mm.M}, {&sym.C_total, &mm.C}, {&sym.K, &mm.K}, {&sym.B, &mm.B},
        {&sym.Cd, &mm.Cd}, {&sym.Cv, &mm.Cv}, {&sym.Ca, &mm.Ca}};
    for (const auto& [exact, numeric] : pairs) {
      REQUIRE(numeric->rows() == static_cast<Eigen::Index>(exact->rows()));
      REQUIRE(numeric->cols() == static_cast<Eigen::Index>(exact->cols()));
      const double scale = std::max(1.0, numeric->cwiseAbs().maxCoeff());
      for (unsigned r = 0; r < exact->rows(); ++r)
        for (unsigned c = 0; c < exact->cols(); ++c)
          CHECK(std::abs((*numeric)(r, c) - evalf_at((*exact)(r, c), sym, p)) <= 1e-13 * scale);
    }
  }
}

}  // namespace

TEST_CASE("the evaluator agrees with exact evaluation of the symbolic matrices", "[evaluator]") {
  check_against_ginac(mbgen::test::example_model_path("mdof2"));
  check_against_ginac(mbgen::test::example_model_path("spindle"));
}

TEST_CASE("the evaluator's derivatives agree with central differences", "[evaluator]") {
  const ir::ModelIr model = frontend::parse_file(mbgen::test::example_model_path("spindle"));
  const auto eval = evaluator::make_evaluator(model);
  const Eigen::VectorXd p = random_values(eval->info(), 7);
  ModelDerivatives d;
  eval->derivatives(p, d);
  // Densify the sparse derivative of K and compare with differences of K for every parameter.
  const Eigen::Index np = p.size();
  for (Eigen::Index j = 0; j < np; ++j) {
    const double h = 1e-6 * std::max(std::abs(p[j]), 1e-3);
    Eigen::VectorXd hi = p, lo = p;
    hi[j] += h;
    lo[j] -= h;
    ModelMatrices a, b, centre;
    eval->evaluate(hi, a);
    eval->evaluate(lo, b);
    eval->evaluate(p, centre);
    Eigen::MatrixXd dK = Eigen::MatrixXd::Zero(centre.K.rows(), centre.K.cols());
    Eigen::MatrixXd dM = dK;
    for (const DerivativeEntry& e : d.K)
      if (e.param == j) dK(e.row, e.col) += e.value;
    for (const DerivativeEntry& e : d.M)
      if (e.param == j) dM(e.row, e.col) += e.value;
    const Eigen::MatrixXd fdK = (a.K - b.K) / (2 * h), fdM = (a.M - b.M) / (2 * h);
    CHECK((dK - fdK).norm() <= 1e-6 * std::max(1.0, fdK.norm()) + 1e-9 * centre.K.norm());
    CHECK((dM - fdM).norm() <= 1e-6 * std::max(1.0, fdM.norm()) + 1e-9 * centre.M.norm());
  }
}

TEST_CASE("the evaluator reports the model's metadata", "[evaluator]") {
  const ir::ModelIr model = frontend::parse_file(mbgen::test::example_model_path("mdof2"));
  const auto eval = evaluator::make_evaluator(model);
  const ModelInfo& info = eval->info();
  CHECK(info.name == "mdof2");
  REQUIRE(info.parameter_index("k11") >= 0);
  const ParameterInfo& k11 = info.parameters[static_cast<std::size_t>(info.parameter_index("k11"))];
  CHECK(k11.value == 1.38e6);
  CHECK(k11.role == ParameterRole::Estimate);
  CHECK(k11.upper == 1e9);
  CHECK(info.parameters[static_cast<std::size_t>(info.parameter_index("c12"))].role == ParameterRole::Fixed);
  CHECK(info.coordinates == std::vector<std::string>{"mass1.x", "mass2.x"});
  CHECK(info.outputs == std::vector<std::string>{"d1", "d2"});
  CHECK_THROWS_WITH(eval->evaluate(Eigen::VectorXd::Zero(2), *std::make_unique<ModelMatrices>()),
                    "model `mdof2` has 8 parameters, got a vector of 2");
}

// A delay's Pade section near t = 0 is the identity: the FRF of an accelerometer behind it is the plain one at
// every line, the lowest included, with every entry of the matrices bounded (a fit that seeks t -> 0 evaluates
// there). Written for the section's own state, its pivot grew as 1 / t^2 and the FRF at 0.03 Hz was "singular".
TEST_CASE("a delay near zero leaves an accelerometer's FRF as it is, down to the lowest line", "[evaluator]") {
  const std::string plain_text = mbgen::test::example_model_text("mdof2") + "output a2 acceleration of mass2 along x\n";
  const std::string late_text =
      plain_text + "param td = 1e-4 \"s\" estimate in [0, 1e-3]\nfilter late on a2 delay time td sections 2\n";
  const evaluator::SymbolicEvaluator plain(symbolic::derive(frontend::parse_string(plain_text, "plain.mdl")));
  const evaluator::SymbolicEvaluator late(symbolic::derive(frontend::parse_string(late_text, "late.mdl")));
  const int td = late.info().parameter_index("td");
  REQUIRE(td >= 0);
  const std::vector<double> lines = {0.03125, 1.0, 30.0, 200.0};
  const FrfResult expected = frf(plain, plain.info().default_values(), lines);
  for (double t : {1e-12, 1e-30, 1e-200}) {
    Eigen::VectorXd p = late.info().default_values();
    p[td] = t;
    ModelMatrices m;
    late.evaluate(p, m);
    CHECK(m.M.allFinite());
    CHECK(m.C.allFinite());
    CHECK(m.K.allFinite());
    CHECK(m.Cv.allFinite());
    const FrfResult got = frf(late, p, lines);
    const int a2 = plain.info().output_index("a2");
    REQUIRE(late.info().output_index("a2") == a2);
    // The tolerance is far above the delay's own effect (w t <= 1.3e-9) and far below any that matters.
    for (std::size_t k = 0; k < lines.size(); ++k)
      CHECK(std::abs(got.H[k](a2, 0) - expected.H[k](a2, 0)) <= 1e-7 * std::abs(expected.H[k](a2, 0)));
  }
}
