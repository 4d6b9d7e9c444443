#include "symbolic/mechanism.hpp"

namespace mbgen::symbolic {

const BodyKinematics* Mechanism::find(const std::string& frame) const {
  for (const BodyKinematics& b : bodies)
    if (b.body->name == frame) return &b;
  return nullptr;
}

Mechanism make_mechanism(const ir::ModelIr& model, const ParameterTable& params) {
  Mechanism m;
  m.model = &model;
  m.params = &params;
  for (const ir::Body& body : model.bodies) {
    m.bodies.push_back(make_body_kinematics(body, m.coordinate_count, params));
    m.coordinate_count += static_cast<int>(body.dofs.size());
  }
  return m;
}

Row displacement_row(const Mechanism& m, const ir::Attachment& at, const GiNaC::matrix& n) {
  Row row = zero_row(m.coordinate_count);
  const BodyKinematics* b = m.find(at.frame);
  if (!b) return row;
  const std::vector<GiNaC::matrix> jac = point_jacobian_at_rest(*b, to_column(at.point, *m.params));
  for (size_t i = 0; i < jac.size(); ++i) row[b->coordinate[i]] = tidy(dot(n, jac[i]));
  return row;
}

std::array<Row, 3> displacement_rows(const Mechanism& m, const ir::Attachment& at) {
  std::array<Row, 3> rows = {zero_row(m.coordinate_count), zero_row(m.coordinate_count), zero_row(m.coordinate_count)};
  const BodyKinematics* b = m.find(at.frame);
  if (!b) return rows;
  const std::vector<GiNaC::matrix> jac = point_jacobian_at_rest(*b, to_column(at.point, *m.params));
  for (size_t i = 0; i < jac.size(); ++i)
    for (unsigned a = 0; a < 3; ++a) rows[a][b->coordinate[i]] = tidy(jac[i](a, 0));  // = displacement_row's e_a^T
  return rows;
}

Row rotation_row(const Mechanism& m, const std::string& frame, const GiNaC::matrix& n) {
  Row row = zero_row(m.coordinate_count);
  const BodyKinematics* b = m.find(frame);
  if (!b) return row;
  GiNaC::matrix theta(3, 1);
  for (size_t i = 0; i < b->q.size(); ++i) {
    const int d = static_cast<int>(b->body->dofs[i]);
    if (d >= 3) theta(d - 3, 0) = b->q[i];
  }
  const GiNaC::ex projected = dot(n, theta);
  for (size_t i = 0; i < b->q.size(); ++i) row[b->coordinate[i]] = tidy(projected.diff(b->q[i]));
  return row;
}

Row moment_row(const Mechanism& m, const std::string& frame, const GiNaC::matrix& n) {
  Row row = zero_row(m.coordinate_count);
  const BodyKinematics* b = m.find(frame);
  if (!b) return row;
  const GiNaC::ex projected = dot(n, angular_velocity(*b));
  const GiNaC::exmap rest = b->at_rest();
  for (size_t i = 0; i < b->q.size(); ++i) row[b->coordinate[i]] = tidy(projected.diff(b->qd[i]).subs(rest));
  return row;
}

}  // namespace mbgen::symbolic
