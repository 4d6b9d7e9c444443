// The mdof2 reference model (docs/reference-models.md, Table 5.1) written once for the tests: its values, its
// transfer functions in closed form, its matrices assembled by hand, and the model as an mbgen::Model (a
// LinearModel, independent of the compiler). Header-only; include from *_test.cpp files only.
#pragma once

#include "mbgen_test/linear_model.hpp"

#include "mbgen/model.hpp"

#include <Eigen/Core>

#include <cmath>
#include <complex>
#include <limits>

namespace mbgen::test {

// mdof2 truth (docs/reference-models.md, Table 5.1), in the order m1, m2, k11, k22, k12, c11, c22, c12.
struct Mdof2Values {
  double m1 = 1.39, m2 = 1.09, k11 = 1.38e6, k22 = 0.24e6, k12 = 0.12e6, c11 = 13.42, c22 = 0.47, c12 = 0;
};

// G11 = d1/F1 and G21 = d2/F1 from the closed-form coefficients of docs/reference-models.md.
inline std::complex<double> mdof2_g11(const Mdof2Values& v, double f_hz) {
  const std::complex<double> s(0, 2 * std::acos(-1.0) * f_hz);
  const double mm = v.m1 * v.m2;
  const double a3 = (v.c11 * v.m2 + v.c12 * v.m1 + v.c12 * v.m2 + v.c22 * v.m1) / mm;
  const double a2 = (v.c11 * v.c12 + v.c11 * v.c22 + v.c12 * v.c22 + v.k11 * v.m2 + v.k12 * v.m1 + v.k12 * v.m2 +
                     v.k22 * v.m1) / mm;
  const double a1 = (v.c11 * v.k12 + v.c11 * v.k22 + v.c12 * v.k11 + v.c12 * v.k22 + v.c22 * v.k11 + v.c22 * v.k12) / mm;
  const double a0 = (v.k11 * v.k12 + v.k11 * v.k22 + v.k12 * v.k22) / mm;
  const std::complex<double> den = s * s * s * s + a3 * s * s * s + a2 * s * s + a1 * s + a0;
  const std::complex<double> num = (1 / v.m1) * s * s + (v.c12 + v.c22) / mm * s + (v.k12 + v.k22) / mm;
  return num / den;
}
inline std::complex<double> mdof2_g21(const Mdof2Values& v, double f_hz) {
  const std::complex<double> s(0, 2 * std::acos(-1.0) * f_hz);
  const double mm = v.m1 * v.m2;
  const std::complex<double> g11_den = mdof2_g11(v, f_hz) / ((1 / v.m1) * s * s + (v.c12 + v.c22) / mm * s + (v.k12 + v.k22) / mm);
  return g11_den * (v.c12 / mm * s + v.k12 / mm);
}

// M, C, K, B and the output maps of mdof2 at `v`, assembled by hand: coordinates q1, q2 of the two masses, input
// F1 on mass 1, outputs d1 = q1, d2 = q2 and, with `extra_outputs`, v1 = q1' and a2 = q2''.
inline ModelMatrices mdof2_matrices(const Mdof2Values& v = {}, bool extra_outputs = false) {
  ModelMatrices m;
  m.M.resize(2, 2);
  m.M << v.m1, 0, 0, v.m2;
  m.C.resize(2, 2);
  m.C << v.c11 + v.c12, -v.c12, -v.c12, v.c22 + v.c12;
  m.K.resize(2, 2);
  m.K << v.k11 + v.k12, -v.k12, -v.k12, v.k22 + v.k12;
  m.B.resize(2, 1);
  m.B << 1, 0;
  const Eigen::Index outputs = extra_outputs ? 4 : 2;
  m.Cd = Eigen::MatrixXd::Zero(outputs, 2);
  m.Cv = Eigen::MatrixXd::Zero(outputs, 2);
  m.Ca = Eigen::MatrixXd::Zero(outputs, 2);
  m.Cd(0, 0) = 1;
  m.Cd(1, 1) = 1;
  if (extra_outputs) {
    m.Cv(2, 0) = 1;
    m.Ca(3, 1) = 1;
  }
  return m;
}

// mdof2 as a model: parameters in model order m1, m2, k11, k22, k12, c11, c22, c12 (all estimated but c12, which
// is fixed), lower bounds 0 and, with `model_file_bounds`, the upper bounds of examples/mdof2/mdof2.mdl (100 kg,
// 1e9 N/m, 1e4 N s/m), else none. Outputs d1, d2 and, with `extra_outputs`, v1 = q1' and a2 = q2'' (the velocity
// and acceleration paths).
class Mdof2Model : public LinearModel {
 public:
  enum Param { m1, m2, k11, k22, k12, c11, c22, c12, count };

  explicit Mdof2Model(bool extra_outputs = false, const Mdof2Values& v = {}, bool model_file_bounds = false)
      : LinearModel("mdof2", 2, {"F1"}, extra_outputs ? std::vector<std::string>{"d1", "d2", "v1", "a2"}
                                                      : std::vector<std::string>{"d1", "d2"}) {
    using R = ParameterRole;
    const double inf = std::numeric_limits<double>::infinity();
    const double mass_max = model_file_bounds ? 100 : inf, k_max = model_file_bounds ? 1e9 : inf,
                 c_max = model_file_bounds ? 1e4 : inf;
    parameter("m1", v.m1, R::Estimate, 0, mass_max, "kg");
    parameter("m2", v.m2, R::Estimate, 0, mass_max, "kg");
    parameter("k11", v.k11, R::Estimate, 0, k_max, "N/m");
    parameter("k22", v.k22, R::Estimate, 0, k_max, "N/m");
    parameter("k12", v.k12, R::Estimate, 0, k_max, "N/m");
    parameter("c11", v.c11, R::Estimate, 0, c_max, "N s/m");
    parameter("c22", v.c22, R::Estimate, 0, c_max, "N s/m");
    parameter("c12", v.c12, R::Fixed, 0, inf, "N s/m");
    linear(M, Param::m1, 0, 0, 1);
    linear(M, Param::m2, 1, 1, 1);
    element(K, Param::k11, 0, -1);
    element(K, Param::k22, 1, -1);
    element(K, Param::k12, 0, 1);
    element(C, Param::c11, 0, -1);
    element(C, Param::c22, 1, -1);
    element(C, Param::c12, 0, 1);
    constant(B, 0, 0, 1);
    constant(Cd, 0, 0, 1);
    constant(Cd, 1, 1, 1);
    if (extra_outputs) {
      constant(Cv, 2, 0, 1);
      constant(Ca, 3, 1, 1);
    }
  }
};

// mdof2 with the given values (the estimators' tests: the truth, or a prior).
inline Mdof2Model mdof2_model(const Mdof2Values& v = {}, bool model_file_bounds = false) {
  return Mdof2Model(false, v, model_file_bounds);
}

}  // namespace mbgen::test
