#include "symbolic/checks.hpp"

#include <vector>

#include "frontend/diagnostics.hpp"
#include "symbolic/geometry.hpp"

namespace mbgen::symbolic {

namespace {

bool row_is_zero(const GiNaC::matrix& mat, int i) {
  for (unsigned j = 0; j < mat.cols(); ++j)
    if (!mat(i, j).is_zero()) return false;
  return true;
}

bool is_rotation(ir::Dof d) { return static_cast<int>(d) >= 3; }

// A constant expression (numbers, pi, roots) that is below zero.
bool negative(const GiNaC::ex& e) {
  const GiNaC::ex v = GiNaC::evalf(e);
  return GiNaC::is_a<GiNaC::numeric>(v) && GiNaC::ex_to<GiNaC::numeric>(v).is_real() &&
         GiNaC::ex_to<GiNaC::numeric>(v).is_negative();
}

}  // namespace

void check_every_coordinate_is_held(const Mechanism& m, const SymbolicModel& sm) {
  for (const BodyKinematics& b : m.bodies)
    for (size_t k = 0; k < b.coordinate.size(); ++k) {
      const int i = b.coordinate[k];
      if (!row_is_zero(sm.K, i) || !row_is_zero(sm.C_total, i)) continue;
      const std::string dof = ir::to_string(b.body->dofs[k]);
      throw frontend::ModelError(m.model->file, b.body->loc,
                                 "coordinate " + sm.coordinates[i].name() +
                                     ": no element acts on it (its stiffness and damping rows are zero); attach "
                                     "an element to body `" + b.body->name + "` that resists " + dof +
                                     ", or remove " + dof + " from its dof list");
    }
}

void check_mass_matrix(const Mechanism& m, const SymbolicModel& sm) {
  const GiNaC::exmap values = sm.values();
  for (const BodyKinematics& b : m.bodies) {
    const unsigned n = static_cast<unsigned>(b.coordinate.size());
    GiNaC::matrix block(n, n);
    for (unsigned r = 0; r < n; ++r)
      for (unsigned c = 0; c < n; ++c) block(r, c) = tidy(sm.M(b.coordinate[r], b.coordinate[c]).subs(values));
    for (unsigned k = 0; k < n; ++k) {
      if (!block(k, k).is_zero()) continue;
      const ir::Dof dof = b.body->dofs[k];
      const std::string what = is_rotation(dof) ? std::string("inertia about ") + ir::to_string(dof)[1]
                                                : std::string("mass");
      throw frontend::ModelError(m.model->file, b.body->loc,
                                 "coordinate " + sm.coordinates[b.coordinate[k]].name() + " has zero " + what +
                                     " at the current parameter values (singular mass matrix); give body `" +
                                     b.body->name + "` a non-zero " +
                                     (is_rotation(dof) ? "inertia (inertia XX, YY, ZZ)" : "mass") +
                                     ", or remove " + ir::to_string(dof) + " from its dof list");
    }
    // Kinetic energy must be positive: a negative mass or inertia gives modes with negative damping ratios that
    // mean nothing. Sylvester's criterion, on the exact minors evaluated to their sign.
    for (unsigned k = 0; k < n; ++k) {
      if (!negative(block(k, k))) continue;
      const ir::Dof dof = b.body->dofs[k];
      throw frontend::ModelError(m.model->file, b.body->loc,
                                 "coordinate " + sm.coordinates[b.coordinate[k]].name() + " has a negative " +
                                     (is_rotation(dof) ? std::string("inertia about ") + ir::to_string(dof)[1]
                                                       : std::string("mass")) +
                                     " at the current parameter values; masses and inertias must be positive");
    }
    // Sylvester's criterion through an exact LDL^T factorization: the k-th leading minor is d_1 ... d_k, and while
    // the earlier minors are positive its sign is the sign of d_k. O(n^3) exact operations instead of the minors'
    // expansion (exponential); the messages are the same.
    std::vector<GiNaC::ex> d(n);
    GiNaC::matrix l(n, n);  // unit lower triangular, below the diagonal
    for (unsigned k = 0; k < n; ++k) {
      GiNaC::ex dk = block(k, k);
      for (unsigned j = 0; j < k; ++j) dk -= l(k, j) * l(k, j) * d[j];
      d[k] = tidy(dk);
      if (k >= 1 && (negative(d[k]) || (k + 1 < n && d[k].is_zero())))  // a zero last pivot has its message below
        throw frontend::ModelError(m.model->file, b.body->loc,
                                   "the mass matrix of body `" + b.body->name +
                                       "` is not positive definite at the current parameter values (its inertia "
                                       "tensor is not physical: check its inertia values)");
      if (d[k].is_zero()) break;
      for (unsigned i = k + 1; i < n; ++i) {
        GiNaC::ex lik = block(i, k);
        for (unsigned j = 0; j < k; ++j) lik -= l(i, j) * l(k, j) * d[j];
        l(i, k) = tidy(lik / d[k]);
      }
    }
    if (n > 0 && d[n - 1].is_zero())
      throw frontend::ModelError(m.model->file, b.body->loc,
                                 "the mass matrix of body `" + b.body->name +
                                     "` is singular at the current parameter values (its inertia tensor is not "
                                     "positive definite on its rotation coordinates); check its inertia values");
  }
}

}  // namespace mbgen::symbolic
