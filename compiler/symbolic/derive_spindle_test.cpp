// spindle (docs/reference-models.md): natural frequencies, symmetry, uncoupled blocks, and gyroscopic coupling.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "mbgen_test/files.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/test_support.hpp"

using namespace mbgen;
using namespace mbgen::symbolic;
using namespace mbgen::symbolic::test;

namespace {

std::string example_text(const std::string& name) { return mbgen::test::example_model_text(name); }

bool symmetric(const GiNaC::matrix& m) {
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j)
      if (!(m(i, j) - m(j, i)).is_zero()) return false;  // tidy entries: equal ones compare equal as they are
  return true;
}

std::vector<std::string> names(const SymbolicModel& sm, const std::vector<int>& block) {
  std::vector<std::string> r;
  for (int i : block) r.push_back(sm.coordinates[i].name());
  return r;
}

int index_of(const SymbolicModel& sm, const std::string& name) {
  for (size_t i = 0; i < sm.coordinates.size(); ++i)
    if (sm.coordinates[i].name() == name) return static_cast<int>(i);
  return -1;
}

}  // namespace

TEST_CASE("spindle: undamped natural frequencies match the reference list") {
  const ir::ModelIr model = load_example("spindle");
  const SymbolicModel sm = derive(model);
  const GiNaC::exmap values = sm.values();
  const Eigen::MatrixXd M = to_eigen(sm.M, values), K = to_eigen(sm.K, values);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  REQUIRE(eig.info() == Eigen::Success);
  const std::vector<double> reference = {212.1, 231.2, 276.1, 285.4, 451.4, 526.1,
                                         639.7, 744.1, 814.8, 869.1, 1103.0};
  REQUIRE(eig.eigenvalues().size() == static_cast<int>(reference.size()));
  for (size_t i = 0; i < reference.size(); ++i) {
    const double f = std::sqrt(eig.eigenvalues()[i]) / (2 * M_PI);
    INFO("mode " << i + 1 << ": " << f << " Hz");
    CHECK(f == Approx(reference[i]).epsilon(1e-3));
  }
}

TEST_CASE("spindle: symmetric matrices, no gyroscopic terms at nominal, two uncoupled blocks") {
  const ir::ModelIr model = load_example("spindle");
  const SymbolicModel sm = derive(model);
  CHECK(symmetric(sm.M));
  CHECK(symmetric(sm.C));
  CHECK(symmetric(sm.K));
  CHECK(same(sm.G, GiNaC::matrix(11, 11)));
  REQUIRE(sm.blocks.size() == 2);
  CHECK(names(sm, sm.blocks[0]) ==
        std::vector<std::string>{"spindle.x", "spindle.ry", "housing.x", "housing.ry", "housing.rz"});
  CHECK(names(sm, sm.blocks[1]) == std::vector<std::string>{"spindle.y", "spindle.z", "spindle.rx", "housing.y",
                                                              "housing.z", "housing.rx"});
  // The spindle's inertias are derived: M holds their definitions in the free parameters.
  const GiNaC::ex m_s = symbol_of(sm, "m_s"), L_s = symbol_of(sm, "L_s"), R_so = symbol_of(sm, "R_so"),
                  R_si = symbol_of(sm, "R_si");
  const int rx = index_of(sm, "spindle.rx");
  CHECK(same(sm.M(rx, rx), m_s * (3 * (R_so * R_so + R_si * R_si) + L_s * L_s) / 12));
  // Every transfer function lives in the x/ry/rz block (the input and outputs are along x), exactly, numerically.
  REQUIRE(sm.transfer_functions.size() == 3);
  for (const TransferFunction& tf : sm.transfer_functions) {
    CHECK(tf.coordinates == sm.blocks[0]);
    CHECK_FALSE(tf.symbolic);
    REQUIRE(tf.denominator.size() == 11);
    CHECK(tf.denominator.back() == 1);
    for (const GiNaC::ex& c : tf.denominator) CHECK(GiNaC::is_a<GiNaC::numeric>(c));
    for (const GiNaC::ex& c : tf.numerator) CHECK(GiNaC::is_a<GiNaC::numeric>(c));
  }
}

TEST_CASE("spindle: spin about z gives the skew-symmetric gyroscopic matrix J_szz Omega on rx, ry") {
  const std::string text = example_text("spindle") + "\nspin spindle about z speed n_sp\n";
  const ir::ModelIr model = frontend::parse_string(text, "spindle_spinning.mdl");
  DeriveOptions options;
  options.set["n_sp"] = "100";
  const SymbolicModel sm = derive(model, options);
  const int rx = index_of(sm, "spindle.rx"), ry = index_of(sm, "spindle.ry");
  const GiNaC::ex m_s = symbol_of(sm, "m_s"), R_so = symbol_of(sm, "R_so"), R_si = symbol_of(sm, "R_si"),
                  n_sp = symbol_of(sm, "n_sp");
  const GiNaC::ex J_szz = m_s * (R_so * R_so + R_si * R_si) / 2;
  const GiNaC::ex omega = 2 * GiNaC::Pi * n_sp;
  // Independent route, Euler's equations of an axisymmetric rotor with small tilts theta_x, theta_y: the
  // angular momentum is H = (Jt theta_x' + Jp Omega theta_y, Jt theta_y' - Jp Omega theta_x, Jp Omega), so
  // dH/dt = moment gives  Jt theta_x'' + Jp Omega theta_y' = M_x,  Jt theta_y'' - Jp Omega theta_x' = M_y.
  for (unsigned i = 0; i < 11; ++i)
    for (unsigned j = 0; j < 11; ++j) {
      GiNaC::ex expected = 0;
      if (static_cast<int>(i) == rx && static_cast<int>(j) == ry) expected = J_szz * omega;
      if (static_cast<int>(i) == ry && static_cast<int>(j) == rx) expected = -J_szz * omega;
      INFO(sm.coordinates[i].name() << ", " << sm.coordinates[j].name() << ": " << sm.G(i, j));
      CHECK(same(sm.G(i, j), expected));
      CHECK(same(sm.C_total(i, j), sm.C(i, j) + expected));
    }
  CHECK(to_double(sm.G(rx, ry), sm.values()) == Approx(0.0042360 * 2 * M_PI * 100).epsilon(1e-4));
  // The spin adds no stiffness for an axisymmetric rotor and leaves the mass matrix alone.
  const SymbolicModel still = derive(load_example("spindle"), {{}, false});
  const GiNaC::exmap rename = rename_symbols(still, sm);
  CHECK(same(sm.K, substituted(still.K, rename)));
  CHECK(same(sm.M, substituted(still.M, rename)));
  CHECK_FALSE(same(sm.M, substituted(still.K, rename)));  // the comparison can fail
  // The coupling joins the two planes into one block.
  REQUIRE(sm.blocks.size() == 1);
}
