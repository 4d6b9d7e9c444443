#include "symbolic/kinematics.hpp"

#include "symbolic/geometry.hpp"

namespace mbgen::symbolic {

namespace {

GiNaC::matrix identity4() {
  GiNaC::matrix h(4, 4);
  for (unsigned i = 0; i < 4; ++i) h(i, i) = 1;
  return h;
}

GiNaC::matrix translation4(const GiNaC::matrix& t) {
  GiNaC::matrix h = identity4();
  for (unsigned i = 0; i < 3; ++i) h(i, 3) = t(i, 0);
  return h;
}

// Rotation by angle a about global axis `axis` (0 = x, 1 = y, 2 = z), as a 4x4 transform.
GiNaC::matrix rotation4(unsigned axis, const GiNaC::ex& a) {
  GiNaC::matrix h = identity4();
  const unsigned i = (axis + 1) % 3, j = (axis + 2) % 3;
  h(i, i) = GiNaC::cos(a);
  h(i, j) = -GiNaC::sin(a);
  h(j, i) = GiNaC::sin(a);
  h(j, j) = GiNaC::cos(a);
  return h;
}

GiNaC::matrix diff_matrix(const GiNaC::matrix& m, const GiNaC::symbol& x) {
  GiNaC::matrix d(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) d(i, j) = m(i, j).diff(x);
  return d;
}

}  // namespace

GiNaC::matrix BodyKinematics::rotation() const {
  GiNaC::matrix r(3, 3);
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = 0; j < 3; ++j) r(i, j) = transform(i, j);
  return r;
}

GiNaC::exmap BodyKinematics::at_rest() const {
  GiNaC::exmap m;
  for (size_t i = 0; i < q.size(); ++i) {
    m[q[i]] = 0;
    m[qd[i]] = 0;
  }
  return m;
}

int BodyKinematics::local_index(ir::Dof d) const {
  for (size_t i = 0; i < body->dofs.size(); ++i)
    if (body->dofs[i] == d) return static_cast<int>(i);
  return -1;
}

BodyKinematics make_body_kinematics(const ir::Body& body, int first_coordinate, const ParameterTable& params) {
  BodyKinematics b;
  b.body = &body;
  b.mass = params.convert(body.mass);
  b.centre = to_column(body.position, params);
  // Tensor entries in the order xx, yy, zz, xy, xz, yz (absent = 0).
  static const unsigned row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
  for (unsigned k = 0; k < 6; ++k) {
    const GiNaC::ex v = body.inertia[k] ? params.convert(*body.inertia[k]) : GiNaC::ex(0);
    b.inertia(row[k], col[k]) = v;
    b.inertia(col[k], row[k]) = v;
  }
  GiNaC::matrix t(3, 1);
  GiNaC::matrix rot = identity4();
  GiNaC::ex angle[3] = {0, 0, 0};
  for (size_t i = 0; i < body.dofs.size(); ++i) {
    const std::string name = body.name + "." + ir::to_string(body.dofs[i]);
    b.coordinate.push_back(first_coordinate + static_cast<int>(i));
    b.q.emplace_back(name);
    b.qd.emplace_back(name + "_dot");
    const int d = static_cast<int>(body.dofs[i]);
    if (d < 3)
      t(d, 0) = b.q.back();
    else
      angle[d - 3] = b.q.back();
  }
  for (unsigned axis = 0; axis < 3; ++axis)
    if (!angle[axis].is_zero()) rot = rot.mul(rotation4(axis, angle[axis]));
  GiNaC::matrix minus_c0(3, 1);
  for (unsigned i = 0; i < 3; ++i) minus_c0(i, 0) = -b.centre(i, 0);
  b.transform = translation4(b.centre.add(t)).mul(rot).mul(translation4(minus_c0));
  return b;
}

GiNaC::matrix point_position(const BodyKinematics& b, const GiNaC::matrix& p) {
  GiNaC::matrix h(4, 1);
  for (unsigned i = 0; i < 3; ++i) h(i, 0) = p(i, 0);
  h(3, 0) = 1;
  const GiNaC::matrix r4 = b.transform.mul(h);
  GiNaC::matrix r(3, 1);
  for (unsigned i = 0; i < 3; ++i) r(i, 0) = r4(i, 0);
  return r;
}

GiNaC::matrix point_velocity(const BodyKinematics& b, const GiNaC::matrix& p) {
  const GiNaC::matrix r = point_position(b, p);
  GiNaC::matrix v(3, 1);
  for (size_t i = 0; i < b.q.size(); ++i) v = v.add(diff_matrix(r, b.q[i]).mul_scalar(b.qd[i]));
  return v;
}

std::vector<GiNaC::matrix> point_jacobian_at_rest(const BodyKinematics& b, const GiNaC::matrix& p) {
  const GiNaC::matrix r = point_position(b, p);
  const GiNaC::exmap rest = b.at_rest();
  std::vector<GiNaC::matrix> jac;
  for (size_t i = 0; i < b.q.size(); ++i) {
    GiNaC::matrix d = diff_matrix(r, b.q[i]);
    for (unsigned k = 0; k < 3; ++k) d(k, 0) = tidy(d(k, 0).subs(rest));
    jac.push_back(d);
  }
  return jac;
}

GiNaC::matrix angular_velocity(const BodyKinematics& b) {
  const GiNaC::matrix r = b.rotation();
  GiNaC::matrix r_dot(3, 3);
  for (size_t i = 0; i < b.q.size(); ++i) r_dot = r_dot.add(diff_matrix(r, b.q[i]).mul_scalar(b.qd[i]));
  const GiNaC::matrix w = r_dot.mul(r.transpose());  // skew-symmetric [w]x
  GiNaC::matrix omega(3, 1);
  omega(0, 0) = w(2, 1);
  omega(1, 0) = w(0, 2);
  omega(2, 0) = w(1, 0);
  return omega;
}

}  // namespace mbgen::symbolic
