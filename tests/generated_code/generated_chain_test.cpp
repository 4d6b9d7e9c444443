// Machine scale (issue 14): the emitted code of a 96-coordinate chain, whole (one translation unit, functions
// unbounded) and split (functions of at most 500 operations, three translation units; tests/generated_code/
// CMakeLists.txt), against each other and against the derivation: matrices, Jacobians, state space, the runtime
// adapter and the run-time transfer functions (long double: in double a_0 ~ 1e630 does not exist).
#include <catch2/catch.hpp>

#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include "chain_split_model.hpp"
#include "chain_whole_model.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/test_chain_model.hpp"

namespace {

namespace whole = generated::chain_whole;
namespace split = generated::chain_split;

template <typename S>
using Dyn = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;

std::string read(const std::string& name) {
  std::ifstream in(std::string(MBGEN_GENERATED_DIR) + "/" + name);
  REQUIRE(in);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Parameters near the defaults, drawn from a seed.
template <typename S>
std::vector<S> parameters(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.8, 1.2);
  std::vector<S> p;
  for (double v : whole::parameter_defaults) p.push_back(static_cast<S>(v * u(rng)));
  return p;
}

// The chain's matrix types are dynamic-size (more than 32 coordinates): Dyn<S> itself.
template <typename S>
Dyn<S> as_dyn(void (*fn)(const S*, Dyn<S>&), const S* p) {
  Dyn<S> m;
  fn(p, m);
  return m;
}

template <typename S>
double relative_difference(const Dyn<S>& a, const Dyn<S>& b) {
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.cols() == b.cols());
  const S scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return scale == 0 ? 0.0 : static_cast<double>((a - b).cwiseAbs().maxCoeff() / scale);
}

template <typename S>
std::vector<Dyn<S>> whole_matrices(const S* p) {
  return {as_dyn<S>(&whole::mass_matrix<S>, p), as_dyn<S>(&whole::damping_matrix<S>, p),
          as_dyn<S>(&whole::stiffness_matrix<S>, p), as_dyn<S>(&whole::input_matrix<S>, p),
          as_dyn<S>(&whole::output_displacement_matrix<S>, p), as_dyn<S>(&whole::output_velocity_matrix<S>, p),
          as_dyn<S>(&whole::output_acceleration_matrix<S>, p)};
}

template <typename S>
std::vector<Dyn<S>> split_matrices(const S* p) {
  return {as_dyn<S>(&split::mass_matrix<S>, p), as_dyn<S>(&split::damping_matrix<S>, p),
          as_dyn<S>(&split::stiffness_matrix<S>, p), as_dyn<S>(&split::input_matrix<S>, p),
          as_dyn<S>(&split::output_displacement_matrix<S>, p), as_dyn<S>(&split::output_velocity_matrix<S>, p),
          as_dyn<S>(&split::output_acceleration_matrix<S>, p)};
}

// Definitions of pieces (`void NAME_chunk_K(`) in a source.
int pieces_in(const std::string& text) {
  const std::regex piece("\nvoid [a-z_]+_chunk_[0-9]+\\([^;{]*\\) \\{");
  return static_cast<int>(std::distance(std::sregex_iterator(text.begin(), text.end(), piece), std::sregex_iterator()));
}

}  // namespace

TEST_CASE("chain16: the split source is spread over three files, the whole one has no pieces") {
  static_assert(whole::num_coordinates == 96 && split::num_coordinates == 96, "a chain of 16 bodies");
  CHECK(pieces_in(read("chain_whole_model.cpp")) == 0);
  CHECK(pieces_in(read("chain_split_model.cpp")) == 0);  // declarations only
  const int part1 = pieces_in(read("chain_split_model_part1.cpp")), part2 = pieces_in(read("chain_split_model_part2.cpp"));
  CHECK(part1 > 0);
  CHECK(part2 > 0);
  // Functions of at most 500 operations: the 96-coordinate Jacobians alone have thousands of entries.
  CHECK(part1 + part2 > 10);
}

TEST_CASE("chain16: split and whole code give the same matrices, Jacobians and state space") {
  for (unsigned seed : {1u, 2u}) {
    const std::vector<double> p = parameters<double>(seed);
    const auto a = whole_matrices<double>(p.data()), b = split_matrices<double>(p.data());
    for (std::size_t k = 0; k < a.size(); ++k) {
      INFO("matrix " << k << ", seed " << seed);
      CHECK(relative_difference(a[k], b[k]) < 1e-14);
    }
    const std::vector<long double> pl = parameters<long double>(seed);
    const auto al = whole_matrices<long double>(pl.data()), bl = split_matrices<long double>(pl.data());
    for (std::size_t k = 0; k < al.size(); ++k) CHECK(relative_difference(al[k], bl[k]) < 1e-17);

    // The Jacobians: the same pattern (it is in the headers), values to rounding.
    REQUIRE(whole::stiffness_matrix_jacobian_pattern.size() == split::stiffness_matrix_jacobian_pattern.size());
    for (std::size_t k = 0; k < whole::stiffness_matrix_jacobian_pattern.size(); ++k) {
      CHECK(whole::stiffness_matrix_jacobian_pattern[k].param == split::stiffness_matrix_jacobian_pattern[k].param);
      CHECK(whole::stiffness_matrix_jacobian_pattern[k].row == split::stiffness_matrix_jacobian_pattern[k].row);
      CHECK(whole::stiffness_matrix_jacobian_pattern[k].col == split::stiffness_matrix_jacobian_pattern[k].col);
    }
    auto jacobian_difference = [&](auto whole_fn, auto split_fn, std::size_t size) {
      std::vector<double> x(size + 1), y(size + 1);
      whole_fn(p.data(), x.data());
      split_fn(p.data(), y.data());
      double worst = 0, scale = 0;
      for (std::size_t k = 0; k < size; ++k) worst = std::max(worst, std::fabs(x[k] - y[k])), scale = std::max(scale, std::fabs(x[k]));
      return worst / scale;
    };
    CHECK(jacobian_difference(&whole::mass_matrix_jacobian<double>, &split::mass_matrix_jacobian<double>,
                              whole::mass_matrix_jacobian_pattern.size()) < 1e-14);
    CHECK(jacobian_difference(&whole::damping_matrix_jacobian<double>, &split::damping_matrix_jacobian<double>,
                              whole::damping_matrix_jacobian_pattern.size()) < 1e-14);
    CHECK(jacobian_difference(&whole::stiffness_matrix_jacobian<double>, &split::stiffness_matrix_jacobian<double>,
                              whole::stiffness_matrix_jacobian_pattern.size()) < 1e-14);

    whole::StateMatrix<double> A1, A2;
    whole::StateInputMatrix<double> B1, B2;
    whole::StateOutputMatrix<double> C1, C2;
    whole::FeedthroughMatrix<double> D1, D2;
    whole::state_space(p.data(), A1, B1, C1, D1);
    split::state_space(p.data(), A2, B2, C2, D2);
    REQUIRE(A1.rows() == 192);
    REQUIRE(A1.cols() == 192);
    CHECK(relative_difference<double>(A1, A2) < 1e-12);
    CHECK(relative_difference<double>(B1, B2) < 1e-12);
    CHECK(relative_difference<double>(C1, C2) < 1e-12);
    // A = [[0, I], [-M^-1 K, -M^-1 C]]: M times the lower left block is -K.
    const Dyn<double> MK = a[0] * A1.bottomLeftCorner(96, 96);
    CHECK(relative_difference<double>(MK, -a[2]) < 1e-12);
  }
}

TEST_CASE("chain16: the split code equals the derivation and the in-process evaluator") {
  const std::string text = mbgen::symbolic::test::chain_model_text(16);
  const mbgen::ir::ModelIr ir = mbgen::frontend::parse_string(text, "chain16.mdl");
  const mbgen::symbolic::SymbolicModel sm = mbgen::symbolic::derive(ir, {{}, false});
  REQUIRE(sm.parameters.size() == static_cast<std::size_t>(split::num_parameters));
  // At the defaults, exactly: the generated defaults are the doubles nearest the exact values.
  const std::vector<double> p(split::parameter_defaults.begin(), split::parameter_defaults.end());
  const auto gen = split_matrices<double>(p.data());
  const GiNaC::exmap values = sm.values();
  const GiNaC::matrix* exact[] = {&sm.M, &sm.C_total, &sm.K, &sm.B, &sm.Cd, &sm.Cv, &sm.Ca};
  for (std::size_t k = 0; k < 7; ++k) {
    Dyn<double> e(exact[k]->rows(), exact[k]->cols());
    for (unsigned r = 0; r < exact[k]->rows(); ++r)
      for (unsigned c = 0; c < exact[k]->cols(); ++c)
        e(r, c) = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf((*exact[k])(r, c).subs(values))).to_double();
    INFO("matrix " << k);
    CHECK(relative_difference(gen[k], e) < 1e-14);
  }

  // The runtime adapter against the evaluator at drawn parameters: matrices and derivative entries.
  const auto generated_model = split::make_model();
  const auto evaluator = mbgen::evaluator::make_evaluator(ir, {{}, false});
  const std::vector<double> drawn = parameters<double>(3);
  const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(drawn.data(), static_cast<Eigen::Index>(drawn.size()));
  mbgen::ModelMatrices x, y;
  generated_model->evaluate(q, x);
  evaluator->evaluate(q, y);
  CHECK(relative_difference<double>(x.M, y.M) < 1e-13);
  CHECK(relative_difference<double>(x.C, y.C) < 1e-13);
  CHECK(relative_difference<double>(x.K, y.K) < 1e-13);
  mbgen::ModelDerivatives dx, dy;
  generated_model->derivatives(q, dx);
  evaluator->derivatives(q, dy);
  auto dense = [&](const std::vector<mbgen::DerivativeEntry>& d) {
    Dyn<double> m = Dyn<double>::Zero(96 * split::num_parameters, 96);
    for (const auto& e : d) m(e.param * 96 + e.row, e.col) += e.value;
    return m;
  };
  CHECK(relative_difference<double>(dense(dx.K), dense(dy.K)) < 1e-13);
  CHECK(relative_difference<double>(dense(dx.C), dense(dy.C)) < 1e-13);
  CHECK(relative_difference<double>(dense(dx.M), dense(dy.M)) < 1e-13);
}

TEST_CASE("chain16: run-time transfer functions of split and whole code agree (long double, slow)") {
  const std::vector<long double> p = parameters<long double>(4);
  REQUIRE(whole::transfer_functions.size() == 2);
  // One of the two pairs: 193 complex long double LU factorizations of 96 and 97 rows take ~3 s per call (named
  // slow: the sanitizer pass, at -O0, skips it).
  for (int i = 0; i < 1; ++i) {
    std::vector<long double> n1, d1, n2, d2;
    whole::transfer_function(i, p.data(), n1, d1);
    split::transfer_function(i, p.data(), n2, d2);
    REQUIRE(d1.size() == 193);
    REQUIRE(d2.size() == d1.size());
    REQUIRE(n2.size() == n1.size());
    // Each coefficient's difference times rho^k over the largest |c_j| rho^j, rho = a_0^(1/192): the scale the
    // routine's accuracy is stated in. Both come from M, C, K equal to rounding.
    const long double rho = std::pow(std::fabs(d1[0]), 1.0L / 192);
    auto scaled_difference = [&](const std::vector<long double>& x, const std::vector<long double>& y) {
      long double worst = 0, scale = 0, r = 1;
      for (std::size_t k = 0; k < x.size(); ++k, r *= rho) {
        worst = std::max(worst, std::fabs(x[k] - y[k]) * r);
        scale = std::max(scale, std::fabs(x[k]) * r);
      }
      return static_cast<double>(worst / scale);
    };
    INFO("transfer function " << i);
    CHECK(scaled_difference(d1, d2) < 1e-12);
    CHECK(scaled_difference(n1, n2) < 1e-12);
  }
}
