// Rigid-body kinematics with homogeneous transforms (thesis Sec. 3.2, 3.4; internal).
//
// A body's coordinates are translations (x, y, z) of its centre of mass c0 and rotations (rx, ry, rz) about the
// global axes through it. Its 4x4 transform is
//     H(q) = Trans(c0 + t(q)) * Rot(q) * Trans(-c0),    Rot = Rx(rx) Ry(ry) Rz(rz)   (full sin/cos),
// with only the coordinates the body has, so a point p (global, nominal) moves to r_p(q) = c0 + t(q) + R(q)(p - c0).
// The rotation order does not matter for the linearized equations (it changes only terms of third order).
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "ir/model_ir.hpp"
#include "symbolic/to_ginac.hpp"

namespace mbgen::symbolic {

struct BodyKinematics {
  const ir::Body* body = nullptr;
  std::vector<int> coordinate;       // global coordinate index of each of its dofs (in body.dofs order)
  std::vector<GiNaC::symbol> q, qd;  // local position and velocity symbols, one per dof
  GiNaC::ex mass;
  GiNaC::matrix centre{3, 1};        // c0
  GiNaC::matrix inertia{3, 3};       // about c0, global axes, nominal configuration
  GiNaC::matrix transform{4, 4};     // H(q)

  GiNaC::matrix rotation() const;     // R(q), the upper-left 3x3 block of H
  GiNaC::exmap at_rest() const;       // q -> 0, qd -> 0
  int local_index(ir::Dof d) const;   // index into q, or -1
};

BodyKinematics make_body_kinematics(const ir::Body& body, int first_coordinate, const ParameterTable& params);

// r_p(q) = H(q) [p; 1] as a 3x1 column.
GiNaC::matrix point_position(const BodyKinematics& b, const GiNaC::matrix& p);
// Velocity of a point: sum_i dr_p/dq_i qd_i.
GiNaC::matrix point_velocity(const BodyKinematics& b, const GiNaC::matrix& p);
// dr_p/dq_i at q = 0, one 3x1 column per dof of the body (computed once per point).
std::vector<GiNaC::matrix> point_jacobian_at_rest(const BodyKinematics& b, const GiNaC::matrix& p);
// Angular velocity in global axes, from the skew matrix  dR/dt R^T.
GiNaC::matrix angular_velocity(const BodyKinematics& b);

}  // namespace mbgen::symbolic
