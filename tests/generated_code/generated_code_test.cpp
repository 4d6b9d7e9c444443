// The generated C++ against the symbolic engine it came from (GiNaC, exact rationals), at random parameter values:
// matrices, their sparse Jacobians (vs central differences of the generated code), transfer-function
// coefficients (emitted expressions and the run-time routine), the make_model() adapter, long double.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"
#include "mdof2_model.hpp"
#include "spindle_model.hpp"
#include "spindle_spin_model.hpp"
#include "symbolic/derive.hpp"

namespace {

template <typename S>
using Dyn = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;

template <typename S>
struct Entry {
  int param, row, col;
  S value;
};

template <typename S, typename Pattern>
std::vector<Entry<S>> collect(const Pattern& pattern, void (*jacobian)(const S*, S*), const S* p) {
  std::vector<S> values(pattern.size() + 1);
  jacobian(p, values.data());
  std::vector<Entry<S>> out;
  for (std::size_t k = 0; k < pattern.size(); ++k) out.push_back({pattern[k].param, pattern[k].row, pattern[k].col, values[k]});
  return out;
}

// Uniform access to one generated model: matrices in the order M, C, K, B, Cd, Cv, Ca.
#define GENERATED_MODEL(NS, PATH)                                                                               \
  struct NS##_model {                                                                                            \
    static std::string path() { return PATH; }                                                                   \
    static constexpr int num_parameters = generated::NS::num_parameters;                                         \
    template <typename S>                                                                                        \
    static std::vector<Dyn<S>> matrices(const S* p) {                                                            \
      namespace g = generated::NS;                                                                               \
      g::CoordinateMatrix<S> M, C, K;                                                                            \
      g::InputMatrix<S> B;                                                                                       \
      g::OutputMatrix<S> Cd, Cv, Ca;                                                                             \
      g::mass_matrix(p, M), g::damping_matrix(p, C), g::stiffness_matrix(p, K), g::input_matrix(p, B);           \
      g::output_displacement_matrix(p, Cd), g::output_velocity_matrix(p, Cv), g::output_acceleration_matrix(p, Ca); \
      return {M, C, K, B, Cd, Cv, Ca};                                                                           \
    }                                                                                                            \
    template <typename S>                                                                                        \
    static std::vector<std::vector<Entry<S>>> jacobians(const S* p) {                                            \
      namespace g = generated::NS;                                                                               \
      return {collect(g::mass_matrix_jacobian_pattern, &g::mass_matrix_jacobian<S>, p),                         \
              collect(g::damping_matrix_jacobian_pattern, &g::damping_matrix_jacobian<S>, p),                   \
              collect(g::stiffness_matrix_jacobian_pattern, &g::stiffness_matrix_jacobian<S>, p),               \
              collect(g::input_matrix_jacobian_pattern, &g::input_matrix_jacobian<S>, p),                       \
              collect(g::output_displacement_matrix_jacobian_pattern, &g::output_displacement_matrix_jacobian<S>, p), \
              collect(g::output_velocity_matrix_jacobian_pattern, &g::output_velocity_matrix_jacobian<S>, p),   \
              collect(g::output_acceleration_matrix_jacobian_pattern, &g::output_acceleration_matrix_jacobian<S>, p)}; \
    }                                                                                                            \
    static const auto& tf_info() { return generated::NS::transfer_functions; }                                  \
    template <typename S>                                                                                        \
    static void tf(int i, const S* p, std::vector<S>& n, std::vector<S>& d) {                                    \
      generated::NS::transfer_function(i, p, n, d);                                                              \
    }                                                                                                            \
    template <typename S>                                                                                        \
    static void tf_jacobian(int i, const S* p, std::vector<S>& n, std::vector<S>& d) {                           \
      generated::NS::transfer_function_jacobian(i, p, n, d);                                                     \
    }                                                                                                            \
    static std::unique_ptr<mbgen::Model> make() { return generated::NS::make_model(); }                          \
  };

GENERATED_MODEL(mdof2, MBGEN_SOURCE_DIR "/examples/mdof2/mdof2.mdl")
GENERATED_MODEL(spindle, MBGEN_SOURCE_DIR "/examples/spindle/spindle.mdl")
GENERATED_MODEL(spindle_spin, MBGEN_SOURCE_DIR "/tests/generated_code/spindle_spin.mdl")

double to_double(const GiNaC::ex& e) { return GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(e)).to_double(); }

// The derived model, kept alive with its IR.
struct Derived {
  mbgen::ir::ModelIr ir;
  mbgen::symbolic::SymbolicModel sm;
  explicit Derived(const std::string& path) : ir(mbgen::frontend::parse_file(path)), sm(mbgen::symbolic::derive(ir)) {}
  std::vector<const GiNaC::matrix*> matrices() const { return {&sm.M, &sm.C_total, &sm.K, &sm.B, &sm.Cd, &sm.Cv, &sm.Ca}; }
};

// Exact random parameter values near the defaults (defaults of 0 get a value in (0, 1]).
GiNaC::exmap random_values(const mbgen::symbolic::SymbolicModel& sm, std::mt19937& rng) {
  std::uniform_int_distribution<int> u(800, 1200);
  GiNaC::exmap m;
  for (const auto& p : sm.parameters)
    m[p.sym] = p.value.is_zero() ? GiNaC::ex(GiNaC::numeric(u(rng), 1200)) : p.value * GiNaC::numeric(u(rng), 1000);
  return m;
}

template <typename S>
std::vector<S> as_vector(const mbgen::symbolic::SymbolicModel& sm, const GiNaC::exmap& values) {
  std::vector<S> p;
  for (const auto& fp : sm.parameters) p.push_back(static_cast<S>(to_double(values.at(fp.sym))));
  return p;
}

double relative_difference(const Dyn<double>& a, const Dyn<double>& b) {
  const double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return scale == 0 ? 0 : (a - b).cwiseAbs().maxCoeff() / scale;
}

template <typename Model>
void check_matrices_against_symbolic() {
  Derived d(Model::path());
  REQUIRE(static_cast<int>(d.sm.parameters.size()) == Model::num_parameters);
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 5; ++trial) {
    const GiNaC::exmap values = random_values(d.sm, rng);
    const std::vector<double> p = as_vector<double>(d.sm, values);
    const auto gen = Model::template matrices<double>(p.data());
    const auto sym = d.matrices();
    for (std::size_t k = 0; k < sym.size(); ++k) {
      const GiNaC::matrix& m = *sym[k];
      Dyn<double> exact(m.rows(), m.cols());
      for (unsigned r = 0; r < m.rows(); ++r)
        for (unsigned c = 0; c < m.cols(); ++c) exact(r, c) = to_double(m(r, c).subs(values));
      INFO("matrix " << k << ", trial " << trial);
      REQUIRE(gen[k].rows() == exact.rows());
      REQUIRE(gen[k].cols() == exact.cols());
      CHECK(relative_difference(gen[k], exact) < 1e-13);
    }
  }
}

// Sparse Jacobians of the generated matrices against central differences of the generated code (long double).
template <typename Model>
void check_jacobians_against_differences() {
  Derived d(Model::path());
  std::mt19937 rng(777);
  const std::vector<long double> p = as_vector<long double>(d.sm, random_values(d.sm, rng));
  const auto jac = Model::template jacobians<long double>(p.data());
  const auto base = Model::template matrices<long double>(p.data());
  for (int j = 0; j < Model::num_parameters; ++j) {
    const long double h = 1e-5L * std::max(std::fabs(p[static_cast<std::size_t>(j)]), 1e-3L);
    auto plus = p, minus = p;
    plus[static_cast<std::size_t>(j)] += h;
    minus[static_cast<std::size_t>(j)] -= h;
    const auto mp = Model::template matrices<long double>(plus.data());
    const auto mm = Model::template matrices<long double>(minus.data());
    for (std::size_t k = 0; k < base.size(); ++k) {
      Dyn<long double> analytic = Dyn<long double>::Zero(base[k].rows(), base[k].cols());
      for (const auto& e : jac[k])
        if (e.param == j) analytic(e.row, e.col) = e.value;
      const Dyn<long double> fd = (mp[k] - mm[k]) / (2 * h);
      const long double scale = std::max<long double>(base[k].cwiseAbs().maxCoeff() / std::max(std::fabs(p[j]), 1e-3L), 1e-30L);
      INFO("matrix " << k << ", parameter " << d.sm.parameters[static_cast<std::size_t>(j)].name);
      CHECK(static_cast<double>((analytic - fd).cwiseAbs().maxCoeff() / scale) < 1e-8);
    }
  }
}

// Transfer functions: emitted symbolic ones at random values vs GiNaC; run-time ones at the defaults vs the exact
// numbers of the symbolic stage (its non-symbolic coefficients are exact at the current values).
template <typename Model>
void check_transfer_functions() {
  Derived d(Model::path());
  REQUIRE(Model::tf_info().size() == d.sm.transfer_functions.size());
  std::mt19937 rng(4242);
  const GiNaC::exmap random = random_values(d.sm, rng);
  const GiNaC::exmap defaults = d.sm.values();
  for (std::size_t i = 0; i < d.sm.transfer_functions.size(); ++i) {
    const auto& tf = d.sm.transfer_functions[i];
    const auto& info = Model::tf_info()[i];
    CHECK(info.output == tf.output);
    CHECK(info.input == tf.input);
    const GiNaC::exmap& values = tf.symbolic ? random : defaults;
    for (int precision = 0; precision < 2; ++precision) {
      std::vector<double> num, den;
      if (precision == 0) {
        const std::vector<double> p = as_vector<double>(d.sm, values);
        Model::template tf<double>(static_cast<int>(i), p.data(), num, den);
      } else {
        const std::vector<long double> p = as_vector<long double>(d.sm, values);
        std::vector<long double> nl, dl;
        Model::template tf<long double>(static_cast<int>(i), p.data(), nl, dl);
        num.assign(nl.begin(), nl.end());
        den.assign(dl.begin(), dl.end());
      }
      REQUIRE(static_cast<int>(num.size()) == info.numerator_size);
      REQUIRE(static_cast<int>(den.size()) == info.denominator_size);
      std::vector<double> exact_num(num.size(), 0.0), exact_den(den.size(), 0.0);
      REQUIRE(tf.numerator.size() <= num.size());
      REQUIRE(tf.denominator.size() == den.size());
      for (std::size_t k = 0; k < tf.numerator.size(); ++k) exact_num[k] = to_double(tf.numerator[k].subs(values));
      for (std::size_t k = 0; k < tf.denominator.size(); ++k) exact_den[k] = to_double(tf.denominator[k].subs(values));
      // Error measure of coefficient k: relative to the largest |c_j| rho^j, rho the frequency scale of the
      // denominator (a_0^(1/n)): the scale the run-time routine's accuracy is stated in.
      const double n = static_cast<double>(den.size() - 1);
      const double rho = n > 0 ? std::pow(std::fabs(exact_den[0]), 1.0 / n) : 1.0;
      auto check = [&](const std::vector<double>& got, const std::vector<double>& exact, const char* what) {
        double scale = 0;
        for (std::size_t k = 0; k < exact.size(); ++k) scale = std::max(scale, std::fabs(exact[k]) * std::pow(rho, k));
        for (std::size_t k = 0; k < exact.size(); ++k) {
          INFO(what << " " << k << " of transfer function " << i << (tf.symbolic ? " (symbolic)" : " (run time)")
                    << (precision ? ", long double" : ", double") << ": got " << got[k] << ", exact " << exact[k]);
          const double err = std::fabs(got[k] - exact[k]) * std::pow(rho, k);
          CHECK(err <= (tf.symbolic ? 1e-13 : 1e-11) * scale);
        }
      };
      check(num, exact_num, "numerator");
      check(den, exact_den, "denominator");
    }
  }
}

// Jacobians of the transfer-function coefficients against central differences of the generated code.
template <typename Model>
void check_transfer_function_jacobians() {
  Derived d(Model::path());
  std::mt19937 rng(99);
  const std::vector<long double> p = as_vector<long double>(d.sm, random_values(d.sm, rng));
  for (std::size_t i = 0; i < Model::tf_info().size(); ++i) {
    const auto& info = Model::tf_info()[i];
    std::vector<long double> dn, dd, n0, d0;
    Model::template tf_jacobian<long double>(static_cast<int>(i), p.data(), dn, dd);
    Model::template tf<long double>(static_cast<int>(i), p.data(), n0, d0);
    REQUIRE(dn.size() == static_cast<std::size_t>(Model::num_parameters * info.numerator_size));
    REQUIRE(dd.size() == static_cast<std::size_t>(Model::num_parameters * info.denominator_size));
    for (int j = 0; j < Model::num_parameters; ++j) {
      const long double h = 1e-5L * std::max(std::fabs(p[static_cast<std::size_t>(j)]), 1e-3L);
      auto plus = p, minus = p;
      plus[static_cast<std::size_t>(j)] += h;
      minus[static_cast<std::size_t>(j)] -= h;
      std::vector<long double> np, dp, nm, dm;
      Model::template tf<long double>(static_cast<int>(i), plus.data(), np, dp);
      Model::template tf<long double>(static_cast<int>(i), minus.data(), nm, dm);
      auto check = [&](const std::vector<long double>& analytic, const std::vector<long double>& vp,
                       const std::vector<long double>& vm, const std::vector<long double>& v0, int size, const char* what) {
        long double scale = 0;
        for (auto x : v0) scale = std::max(scale, std::fabs(x));
        for (int k = 0; k < size; ++k) {
          const long double fd = (vp[static_cast<std::size_t>(k)] - vm[static_cast<std::size_t>(k)]) / (2 * h);
          const long double an = analytic[static_cast<std::size_t>(j * size + k)];
          // Relative to the coefficient's own size over the parameter's size (derivatives scale like c/p).
          const long double ref = std::max(std::fabs(v0[static_cast<std::size_t>(k)]), 1e-12L * scale) /
                                  std::max(std::fabs(p[static_cast<std::size_t>(j)]), 1e-3L);
          INFO(what << " " << k << " of transfer function " << i << ", parameter "
                    << d.sm.parameters[static_cast<std::size_t>(j)].name << ": analytic " << static_cast<double>(an)
                    << ", differences " << static_cast<double>(fd));
          CHECK(static_cast<double>(std::fabs(an - fd) / ref) < 1e-6);
        }
      };
      check(dn, np, nm, n0, info.numerator_size, "numerator");
      check(dd, dp, dm, d0, info.denominator_size, "denominator");
    }
  }
}

template <typename Model>
void check_runtime_adapter() {
  Derived d(Model::path());
  const auto model = Model::make();
  const mbgen::ModelInfo& info = model->info();
  REQUIRE(info.parameters.size() == d.sm.parameters.size());
  for (std::size_t i = 0; i < info.parameters.size(); ++i) {
    CHECK(info.parameters[i].name == d.sm.parameters[i].name);
    CHECK(info.parameters[i].value == to_double(d.sm.parameters[i].value));  // round-trips exactly
  }
  CHECK(info.coordinates.size() == d.sm.coordinates.size());
  CHECK(info.inputs.size() == d.ir.inputs.size());
  CHECK(info.outputs.size() == d.ir.outputs.size());
  const Eigen::VectorXd p = info.default_values();
  mbgen::ModelMatrices mats;
  model->evaluate(p, mats);
  const auto gen = Model::template matrices<double>(p.data());
  CHECK(mats.M == gen[0]);
  CHECK(mats.C == gen[1]);
  CHECK(mats.K == gen[2]);
  CHECK(mats.B == gen[3]);
  CHECK(mats.Ca == gen[6]);
  mbgen::ModelDerivatives der;
  model->derivatives(p, der);
  const auto jac = Model::template jacobians<double>(p.data());
  CHECK(der.K.size() == jac[2].size());
  for (std::size_t k = 0; k < der.K.size() && k < jac[2].size(); ++k) CHECK(der.K[k].value == jac[2][k].value);
  CHECK_THROWS_AS(model->evaluate(Eigen::VectorXd::Zero(1), mats), std::invalid_argument);
}


// The two backends of the runtime's Model interface, generated code and the in-process evaluator, agree to
// rounding at random parameter values: matrices and (densified) parameter derivatives.
template <typename Model>
void check_backends_agree() {
  const auto generated = Model::make();
  const auto evaluated = mbgen::evaluator::make_evaluator(mbgen::frontend::parse_file(Model::path()));
  REQUIRE(generated->info().parameters.size() == evaluated->info().parameters.size());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> factor(0.7, 1.3);
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd p = generated->info().default_values();
    for (Eigen::Index i = 0; i < p.size(); ++i) p[i] = p[i] == 0 ? factor(rng) : p[i] * factor(rng);
    mbgen::ModelMatrices a, b;
    generated->evaluate(p, a);
    evaluated->evaluate(p, b);
    const std::pair<const Eigen::MatrixXd*, const Eigen::MatrixXd*> pairs[] = {
        {&a.M, &b.M}, {&a.C, &b.C}, {&a.K, &b.K}, {&a.B, &b.B}, {&a.Cd, &b.Cd}, {&a.Cv, &b.Cv}, {&a.Ca, &b.Ca}};
    for (const auto& [x, y] : pairs) {
      REQUIRE(x->rows() == y->rows());
      REQUIRE(x->cols() == y->cols());
      CHECK((*x - *y).norm() <= 1e-13 * std::max(1.0, x->norm()));
    }
    mbgen::ModelDerivatives da, db;
    generated->derivatives(p, da);
    evaluated->derivatives(p, db);
    const auto dense = [&](const std::vector<mbgen::DerivativeEntry>& entries, Eigen::Index rows, Eigen::Index cols) {
      std::vector<Eigen::MatrixXd> out(static_cast<std::size_t>(p.size()), Eigen::MatrixXd::Zero(rows, cols));
      for (const auto& e : entries) out[static_cast<std::size_t>(e.param)](e.row, e.col) += e.value;
      return out;
    };
    const std::tuple<const std::vector<mbgen::DerivativeEntry>*, const std::vector<mbgen::DerivativeEntry>*,
                     const Eigen::MatrixXd*>
        entries[] = {{&da.M, &db.M, &a.M}, {&da.C, &db.C, &a.C}, {&da.K, &db.K, &a.K}, {&da.B, &db.B, &a.B}};
    for (const auto& [x, y, shape] : entries) {
      const auto dx = dense(*x, shape->rows(), shape->cols()), dy = dense(*y, shape->rows(), shape->cols());
      for (std::size_t j = 0; j < dx.size(); ++j)
        CHECK((dx[j] - dy[j]).norm() <= 1e-12 * std::max(1.0, dx[j].norm()));
    }
  }
}

}  // namespace

TEST_CASE("mdof2: generated matrices equal the symbolic ones") { check_matrices_against_symbolic<mdof2_model>(); }
TEST_CASE("spindle: generated matrices equal the symbolic ones") { check_matrices_against_symbolic<spindle_model>(); }
TEST_CASE("spinning spindle: generated matrices equal the symbolic ones") {
  check_matrices_against_symbolic<spindle_spin_model>();
}

TEST_CASE("mdof2: matrix Jacobians match central differences") { check_jacobians_against_differences<mdof2_model>(); }
TEST_CASE("spindle: matrix Jacobians match central differences") { check_jacobians_against_differences<spindle_model>(); }
TEST_CASE("spinning spindle: matrix Jacobians match central differences") {
  check_jacobians_against_differences<spindle_spin_model>();
}

TEST_CASE("mdof2: transfer functions equal the symbolic ones") { check_transfer_functions<mdof2_model>(); }
TEST_CASE("spindle: transfer functions equal the symbolic ones") { check_transfer_functions<spindle_model>(); }
TEST_CASE("spinning spindle: transfer functions equal the symbolic ones") {
  check_transfer_functions<spindle_spin_model>();
}

TEST_CASE("mdof2: transfer-function Jacobians match central differences") {
  check_transfer_function_jacobians<mdof2_model>();
}
TEST_CASE("spindle: transfer-function Jacobians match central differences") {
  check_transfer_function_jacobians<spindle_model>();
}
TEST_CASE("spinning spindle: transfer-function Jacobians match central differences") {
  check_transfer_function_jacobians<spindle_spin_model>();
}

TEST_CASE("mdof2: make_model() serves the runtime interface") { check_runtime_adapter<mdof2_model>(); }
TEST_CASE("spindle: make_model() serves the runtime interface") { check_runtime_adapter<spindle_model>(); }

TEST_CASE("mdof2: generated code and the in-process evaluator agree") { check_backends_agree<mdof2_model>(); }
TEST_CASE("spindle: generated code and the in-process evaluator agree") { check_backends_agree<spindle_model>(); }
TEST_CASE("spinning spindle: generated code and the in-process evaluator agree") {
  check_backends_agree<spindle_spin_model>();
}

TEST_CASE("mdof2: state space from the generated code") {
  // x = [q; q']: A = [[0, I], [-M^-1 K, -M^-1 C]] checked entry by entry for the diagonal M of mdof2.
  std::vector<double> p(generated::mdof2::parameter_defaults.begin(), generated::mdof2::parameter_defaults.end());
  generated::mdof2::StateMatrix<double> A;
  generated::mdof2::StateInputMatrix<double> B;
  generated::mdof2::StateOutputMatrix<double> C;
  generated::mdof2::FeedthroughMatrix<double> D;
  generated::mdof2::state_space(p.data(), A, B, C, D);
  const double m1 = p[0], m2 = p[1], k11 = p[2], k22 = p[3], k12 = p[4], c11 = p[5];
  CHECK(A(0, 2) == 1);
  CHECK(A(2, 0) == Approx(-(k11 + k12) / m1).epsilon(1e-14));
  CHECK(A(2, 1) == Approx(k12 / m1).epsilon(1e-14));
  CHECK(A(3, 0) == Approx(k12 / m2).epsilon(1e-14));
  CHECK(A(3, 1) == Approx(-(k12 + k22) / m2).epsilon(1e-14));
  CHECK(A(2, 2) == Approx(-c11 / m1).epsilon(1e-14));
  CHECK(B(2, 0) == Approx(1 / m1).epsilon(1e-14));
  CHECK(C(0, 0) == 1);
  CHECK(D.norm() == 0);
}
