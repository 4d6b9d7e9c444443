// The bodies of a model with their kinematics, and the linear forms (rows over the generalized coordinates)
// that elements, inputs and outputs are built from (internal).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "ir/model_ir.hpp"
#include "symbolic/geometry.hpp"
#include "symbolic/kinematics.hpp"
#include "symbolic/to_ginac.hpp"

namespace mbgen::symbolic {

struct Mechanism {
  const ir::ModelIr* model = nullptr;
  const ParameterTable* params = nullptr;
  std::vector<BodyKinematics> bodies;  // model order
  int coordinate_count = 0;

  const BodyKinematics* find(const std::string& frame) const;  // nullptr for a ground
};

Mechanism make_mechanism(const ir::ModelIr& model, const ParameterTable& params);

// n^T dr_p/dq at q = 0 for point `at.point` fixed to frame `at.frame` (zero for a ground).
Row displacement_row(const Mechanism& m, const ir::Attachment& at, const GiNaC::matrix& n);
// The same for n = e_x, e_y, e_z from one Jacobian of the point (a spring3's three axes).
std::array<Row, 3> displacement_rows(const Mechanism& m, const ir::Attachment& at);
// n^T d(theta)/dq, theta = the frame's rotation coordinates (rx, ry, rz; zero where it has none).
Row rotation_row(const Mechanism& m, const std::string& frame, const GiNaC::matrix& n);
// n^T d(omega)/d(qd) at q = 0: the generalized force of a unit moment about n.
Row moment_row(const Mechanism& m, const std::string& frame, const GiNaC::matrix& n);

}  // namespace mbgen::symbolic
