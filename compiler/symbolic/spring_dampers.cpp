// Stiffness and damping from the potential energy and the dissipation function (thesis Sec. 3.4.3).
#include "frontend/diagnostics.hpp"
#include "symbolic/lagrange.hpp"

namespace mbgen::symbolic {

namespace {

// One spring-damper along a linear form e(q) = h q (+ higher-order terms), unloaded at q = 0:
//   V = 1/2 k e^2  ->  d2V/dq_i dq_j = k (h_i h_j + e d2e/dq_i dq_j) = k h_i h_j at q = 0 since e(0) = 0;
//   D = 1/2 c (h qd)^2  ->  d2D/dqd_i dqd_j = c h_i h_j.
void add_quadratic(GiNaC::matrix& mat, const GiNaC::ex& coefficient, const Row& h) {
  const int n = static_cast<int>(h.size());
  for (int i = 0; i < n; ++i) {
    if (h[i].is_zero()) continue;
    for (int j = 0; j < n; ++j)
      if (!h[j].is_zero()) mat(i, j) = mat(i, j) + coefficient * h[i] * h[j];
  }
}

}  // namespace

void add_spring_dampers(const Mechanism& m, SymbolicModel& out) {
  const ParameterTable& params = *m.params;
  for (const ir::Element& e : m.model->elements) {
    const size_t expected = e.kind == ir::ElementKind::Spring3 ? 3 : 1;
    if (e.stiffness.size() != expected || (!e.damping.empty() && e.damping.size() != expected))
      throw frontend::ModelError(m.model->file, e.loc,
                                 std::string(ir::to_string(e.kind)) + " `" + e.name + "` needs " +
                                     std::to_string(expected) + " stiffness (and damping) value(s)");
    // A spring3's ends: one point Jacobian each for its three axes.
    std::array<Row, 3> rows_b, rows_a;
    if (e.kind == ir::ElementKind::Spring3) {
      rows_b = displacement_rows(m, e.b);
      rows_a = displacement_rows(m, e.a);
    }
    for (size_t axis = 0; axis < expected; ++axis) {
      Row h;
      if (e.kind == ir::ElementKind::Spring3) {
        h = subtract(rows_b[axis], rows_a[axis]);
      } else {
        const GiNaC::matrix n = unit_direction(e.direction, params);
        if (e.kind == ir::ElementKind::Spring)
          h = subtract(displacement_row(m, e.b, n), displacement_row(m, e.a, n));
        else
          h = subtract(rotation_row(m, e.b.frame, n), rotation_row(m, e.a.frame, n));
      }
      add_quadratic(out.K, params.convert(e.stiffness[axis]), h);
      if (!e.damping.empty()) add_quadratic(out.C, params.convert(e.damping[axis]), h);
    }
  }
}

}  // namespace mbgen::symbolic
