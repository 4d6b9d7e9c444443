// A SymbolicModel of mdof2 (docs/reference-models.md) assembled by hand, independent of the symbolic stage:
// M = diag(m1, m2), C = [[c11+c12, -c12], [-c12, c12+c22]], K likewise, B = e1, Cd = I, and the G11, G21
// coefficients as printed in docs/reference-models.md.
#pragma once

#include "symbolic/symbolic_model.hpp"

namespace mbgen::emit::test {

struct Mdof2 {
  symbolic::SymbolicModel sm;
  GiNaC::symbol m1{"m1"}, m2{"m2"}, k11{"k11"}, k22{"k22"}, k12{"k12"}, c11{"c11"}, c22{"c22"}, c12{"c12"};

  Mdof2() {
    auto param = [&](const char* name, const GiNaC::symbol& s, GiNaC::numeric v) {
      sm.parameters.push_back({name, s, v, nullptr});
    };
    param("m1", m1, GiNaC::numeric(139, 100));
    param("m2", m2, GiNaC::numeric(109, 100));
    param("k11", k11, GiNaC::numeric(1380000));
    param("k22", k22, GiNaC::numeric(240000));
    param("k12", k12, GiNaC::numeric(120000));
    param("c11", c11, GiNaC::numeric(1342, 100));
    param("c22", c22, GiNaC::numeric(47, 100));
    param("c12", c12, GiNaC::numeric(0));
    sm.coordinates = {{"mass1", ir::Dof::X, ""}, {"mass2", ir::Dof::X, ""}};
    sm.M = GiNaC::matrix{{m1, 0}, {0, m2}};
    sm.C = GiNaC::matrix{{c11 + c12, -c12}, {-c12, c12 + c22}};
    sm.G = GiNaC::matrix(2, 2);
    sm.C_total = sm.C;
    sm.K = GiNaC::matrix{{k11 + k12, -k12}, {-k12, k12 + k22}};
    sm.B = GiNaC::matrix{{1}, {0}};
    sm.Cd = GiNaC::matrix{{1, 0}, {0, 1}};
    sm.Cv = GiNaC::matrix(2, 2);
    sm.Ca = GiNaC::matrix(2, 2);
    sm.blocks = {{0, 1}};
    const GiNaC::ex mm = m1 * m2;
    std::vector<GiNaC::ex> den = {(k11 * k12 + k11 * k22 + k12 * k22) / mm,
                                  (c11 * k12 + c11 * k22 + c12 * k11 + c12 * k22 + c22 * k11 + c22 * k12) / mm,
                                  (c11 * c12 + c11 * c22 + c12 * c22 + k11 * m2 + k12 * m1 + k12 * m2 + k22 * m1) / mm,
                                  (c11 * m2 + c12 * m1 + c12 * m2 + c22 * m1) / mm, 1};
    sm.transfer_functions.push_back({0, 0, true, {(k12 + k22) / mm, (c12 + c22) / mm, 1 / m1}, den, {0, 1}});
    sm.transfer_functions.push_back({1, 0, true, {k12 / mm, c12 / mm}, den, {0, 1}});
  }
};

}  // namespace mbgen::emit::test
