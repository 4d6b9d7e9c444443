// Mass matrix and gyroscopic coupling from the kinetic energy (thesis Sec. 3.4.2, 3.4.4).
#include <string>

#include "frontend/diagnostics.hpp"
#include "symbolic/lagrange.hpp"

namespace mbgen::symbolic {

namespace {

int axis_index(const std::string& axis) { return axis == "x" ? 0 : axis == "y" ? 1 : axis == "z" ? 2 : -1; }

// The linear time-invariant gyroscopic model needs the spin axis to be a principal axis with equal transverse
// inertias: only then is T independent of the spin angle. Checked on the expressions, so it holds for every
// parameter value (define one transverse inertia in terms of the other).
void check_axisymmetric(const Mechanism& m, const ir::Spin& spin, const BodyKinematics& b, int a) {
  static const char* names = "xyz";
  const int i = (a + 1) % 3, j = (a + 2) % 3;
  const auto fail = [&](const std::string& why) {
    throw frontend::ModelError(m.model->file, spin.loc,
                               "body `" + spin.body + "` cannot spin about " + names[a] + ": " + why +
                                   "; a spin needs a principal axis with equal transverse inertias (products of "
                                   "inertia zero, J" + names[i] + names[i] + " = J" + names[j] + names[j] + ")");
  };
  for (int r = 0; r < 3; ++r)
    for (int c = r + 1; c < 3; ++c)
      if (!tidy(b.inertia(r, c)).is_zero())
        fail(std::string("its product of inertia J") + names[r] + names[c] + " is not zero");
  if (!tidy(b.inertia(i, i) - b.inertia(j, j)).is_zero())
    fail(std::string("its transverse inertias J") + names[i] + names[i] + " and J" + names[j] + names[j] +
         " differ (as expressions)");
}

const ir::Spin* spin_of(const Mechanism& m, const BodyKinematics& b) {
  const ir::Spin* found = nullptr;
  for (const ir::Spin& s : m.model->spins) {
    if (s.body != b.body->name) continue;
    if (found)
      throw frontend::ModelError(m.model->file, s.loc,
                                 "body `" + s.body + "` already spins (line " + std::to_string(found->loc.line) +
                                     "); give one spin statement per body");
    found = &s;
  }
  return found;
}

void add_entry(GiNaC::matrix& mat, int i, int j, const GiNaC::ex& v) { mat(i, j) = mat(i, j) + v; }

}  // namespace

void add_kinetic_energy(const Mechanism& m, SymbolicModel& out) {
  for (const BodyKinematics& b : m.bodies) {
    const GiNaC::matrix v = point_velocity(b, b.centre);
    GiNaC::matrix omega = angular_velocity(b);
    const GiNaC::matrix rot = b.rotation();
    const ir::Spin* spin = spin_of(m, b);
    if (spin) {
      const int a = axis_index(spin->axis);
      if (a < 0)
        throw frontend::ModelError(m.model->file, spin->loc,
                                   "spin axis `" + spin->axis + "` is not x, y or z");
      check_axisymmetric(m, *spin, b, a);
      // The body turns at Omega about its own axis, which the body's rotation carries along: R(q) e_a.
      const GiNaC::ex spin_rate = 2 * GiNaC::Pi * m.params->convert(spin->speed);
      for (unsigned k = 0; k < 3; ++k) omega(k, 0) = omega(k, 0) + spin_rate * rot(k, a);
    }
    const GiNaC::matrix inertia_now = rot.mul(b.inertia).mul(rot.transpose());  // J(q) = R J0 R^T
    const GiNaC::ex kinetic = GiNaC::ex(1) / 2 * b.mass * dot(v, v) +
                              GiNaC::ex(1) / 2 * omega.transpose().mul(inertia_now).mul(omega)(0, 0);
    const GiNaC::exmap rest = b.at_rest();
    const size_t n = b.q.size();
    // M: d2T/dqd dqd at rest. Setting q = 0 before differentiating with respect to qd gives the same result and
    // keeps the expressions small.
    GiNaC::exmap q_rest;
    for (size_t i = 0; i < n; ++i) q_rest[b.q[i]] = 0;
    const GiNaC::ex kinetic_q0 = GiNaC::expand(kinetic.subs(q_rest));
    for (size_t i = 0; i < n; ++i) {
      const GiNaC::ex di = kinetic_q0.diff(b.qd[i]);
      for (size_t j = i; j < n; ++j) {
        const GiNaC::ex mij = tidy(di.diff(b.qd[j]).subs(rest));
        add_entry(out.M, b.coordinate[i], b.coordinate[j], mij);
        if (j != i) add_entry(out.M, b.coordinate[j], b.coordinate[i], mij);
      }
    }
    if (!spin) continue;  // without spin T is a quadratic form in qd: no terms linear in qd and q, none in q only
    for (size_t i = 0; i < n; ++i) {
      const GiNaC::ex dqd = kinetic.diff(b.qd[i]);
      const GiNaC::ex dq = kinetic.diff(b.q[i]);
      for (size_t j = 0; j < n; ++j) {
        const GiNaC::ex a_ij = tidy(dqd.diff(b.q[j]).subs(rest));   // d2T/(dqd_i dq_j)
        const GiNaC::ex a_ji = tidy(dq.diff(b.qd[j]).subs(rest));   // d2T/(dq_i dqd_j)
        add_entry(out.G, b.coordinate[i], b.coordinate[j], a_ij - a_ji);
        // -dT/dq_i contributes -d2T/(dq_i dq_j) q_j: a centrifugal stiffness (zero for an axisymmetric rotor).
        add_entry(out.K, b.coordinate[i], b.coordinate[j], -tidy(dq.diff(b.q[j]).subs(rest)));
      }
    }
  }
}

}  // namespace mbgen::symbolic
