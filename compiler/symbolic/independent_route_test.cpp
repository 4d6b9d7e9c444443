// The Lagrange derivation against an independent assembly from the element geometry:
//   K = sum k h h^T,  C = sum c h h^T,  h = n^T [I, -[p - c0]x] per body (small-rotation kinematics),
//   M = diag(m I, J) per body,  B column = h of the input point,  output row = h of the output point.
#include <catch2/catch.hpp>

#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"
#include "symbolic/test_chain_model.hpp"
#include "symbolic/test_support.hpp"
#include "symbolic/to_ginac.hpp"

using namespace mbgen;
using namespace mbgen::symbolic;
using namespace mbgen::symbolic::test;

namespace {

using Vec = std::array<GiNaC::ex, 3>;

struct Assembler {
  const ir::ModelIr& model;
  const SymbolicModel& sm;
  ParameterTable params;  // its own symbols, renamed to the derivation's ones
  GiNaC::exmap rename;

  Assembler(const ir::ModelIr& m, const SymbolicModel& s) : model(m), sm(s), params(m) {
    for (const FreeParameter& p : params.free_parameters()) rename[p.sym] = symbol_of(sm, p.name);
  }
  GiNaC::ex value(const ir::Expr& e) const { return params.convert(e).subs(rename); }
  Vec point(const ir::Vec3& v) const { return {value(v[0]), value(v[1]), value(v[2])}; }
  Vec unit(const ir::Vec3& v) const {
    const Vec d = point(v);
    const GiNaC::ex length = GiNaC::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return {d[0] / length, d[1] / length, d[2] / length};
  }
  int coordinate(const std::string& body, ir::Dof d) const {
    for (size_t i = 0; i < sm.coordinates.size(); ++i)
      if (sm.coordinates[i].body == body && sm.coordinates[i].dof == d) return static_cast<int>(i);
    return -1;
  }
  // h = n^T dr_p/dq: n_d on translations, n . (e_d x (p - c0)) on rotations.
  std::vector<GiNaC::ex> displacement(const std::string& frame, const Vec& p, const Vec& n) const {
    std::vector<GiNaC::ex> h(sm.coordinates.size(), 0);
    const ir::Body* b = model.find_body(frame);
    if (!b) return h;
    const Vec c = point(b->position);
    const Vec r = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
    for (int d = 0; d < 3; ++d) {
      const int t = coordinate(frame, static_cast<ir::Dof>(d)), a = coordinate(frame, static_cast<ir::Dof>(d + 3));
      if (t >= 0) h[t] = n[d];
      // e_d x r, component-wise.
      const int i = (d + 1) % 3, j = (d + 2) % 3;
      Vec ed_x_r = {0, 0, 0};
      ed_x_r[i] = -r[j];
      ed_x_r[j] = r[i];
      if (a >= 0) h[a] = n[0] * ed_x_r[0] + n[1] * ed_x_r[1] + n[2] * ed_x_r[2];
    }
    return h;
  }
  std::vector<GiNaC::ex> rotation(const std::string& frame, const Vec& n) const {
    std::vector<GiNaC::ex> h(sm.coordinates.size(), 0);
    for (int d = 0; d < 3; ++d) {
      const int a = coordinate(frame, static_cast<ir::Dof>(d + 3));
      if (a >= 0) h[a] = n[d];
    }
    return h;
  }
  static std::vector<GiNaC::ex> minus(const std::vector<GiNaC::ex>& b, const std::vector<GiNaC::ex>& a) {
    std::vector<GiNaC::ex> r(b.size());
    for (size_t i = 0; i < b.size(); ++i) r[i] = b[i] - a[i];
    return r;
  }
  static void add(GiNaC::matrix& m, const GiNaC::ex& k, const std::vector<GiNaC::ex>& h) {
    for (size_t i = 0; i < h.size(); ++i)
      for (size_t j = 0; j < h.size(); ++j) m(i, j) = m(i, j) + k * h[i] * h[j];
  }

  void assemble(GiNaC::matrix& M, GiNaC::matrix& K, GiNaC::matrix& C, GiNaC::matrix& B, GiNaC::matrix& Y) const {
    const unsigned n = static_cast<unsigned>(sm.coordinates.size());
    M = K = C = GiNaC::matrix(n, n);
    B = GiNaC::matrix(n, static_cast<unsigned>(model.inputs.size()));
    Y = GiNaC::matrix(static_cast<unsigned>(model.outputs.size()), n);
    for (const ir::Body& b : model.bodies) {
      static const int row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
      for (int d = 0; d < 3; ++d) {
        const int t = coordinate(b.name, static_cast<ir::Dof>(d));
        if (t >= 0) M(t, t) = value(b.mass);
      }
      for (int k = 0; k < 6; ++k) {
        const int i = coordinate(b.name, static_cast<ir::Dof>(row[k] + 3)),
                  j = coordinate(b.name, static_cast<ir::Dof>(col[k] + 3));
        if (i >= 0 && j >= 0 && b.inertia[k]) M(i, j) = M(j, i) = value(*b.inertia[k]);
      }
    }
    for (const ir::Element& e : model.elements) {
      for (size_t axis = 0; axis < e.stiffness.size(); ++axis) {
        std::vector<GiNaC::ex> h;
        if (e.kind == ir::ElementKind::Torsion) {
          const Vec nn = unit(e.direction.vector);
          h = minus(rotation(e.b.frame, nn), rotation(e.a.frame, nn));
        } else {
          Vec nn = {0, 0, 0};
          if (e.kind == ir::ElementKind::Spring3)
            nn[axis] = 1;
          else
            nn = unit(e.direction.vector);
          h = minus(displacement(e.b.frame, point(e.b.point), nn), displacement(e.a.frame, point(e.a.point), nn));
        }
        add(K, value(e.stiffness[axis]), h);
        if (!e.damping.empty()) add(C, value(e.damping[axis]), h);
      }
    }
    for (size_t u = 0; u < model.inputs.size(); ++u) {
      const ir::Input& in = model.inputs[u];
      const Vec nn = unit(in.direction.vector);
      const auto h = in.kind == ir::InputKind::Force ? displacement(in.at.frame, point(in.at.point), nn)
                                                     : rotation(in.at.frame, nn);
      for (unsigned i = 0; i < n; ++i) B(i, u) = h[i];
    }
    for (size_t o = 0; o < model.outputs.size(); ++o) {
      const ir::Output& y = model.outputs[o];
      const auto h = displacement(y.at.frame, point(y.at.point), unit(y.direction.vector));
      for (unsigned i = 0; i < n; ++i) Y(o, i) = h[i];
    }
  }
};

void compare_with_independent_assembly(const ir::ModelIr& model) {
  const SymbolicModel sm = derive(model, {{}, false});
  const Assembler a(model, sm);
  GiNaC::matrix M, K, C, B, Y;
  a.assemble(M, K, C, B, Y);
  CHECK(same(sm.M, M));
  CHECK(same(sm.K, K));
  CHECK(same(sm.C, C));
  CHECK(same(sm.B, B));
  CHECK(same(sm.Cd.add(sm.Cv).add(sm.Ca), Y));  // each output row is in exactly one of them
  CHECK(same(sm.G, GiNaC::matrix(M.rows(), M.cols())));
  // The comparison is not vacuous.
  CHECK_FALSE(K.is_zero_matrix());
}

}  // namespace

TEST_CASE("independent route: mdof2") { compare_with_independent_assembly(load_example("mdof2")); }

TEST_CASE("independent route: spindle") { compare_with_independent_assembly(load_example("spindle")); }

TEST_CASE("independent route: a chain of 16 six-coordinate bodies (96 coordinates)") {
  compare_with_independent_assembly(frontend::parse_string(chain_model_text(16), "chain16.mdl"));
}

TEST_CASE("independent route: oblique springs, a torsion element, products of inertia, symbolic geometry") {
  const ir::ModelIr model = frontend::parse_string(R"(model oblique
param m = 2
param J1 = 0.1
param k1 = 1000
param k2 = 2000
param k3 = 300
param kt = 50
param c1 = 3
param ct = 0.2
param h = 0.3
ground g
body a {
  mass m
  inertia J1, 2*J1, 3*J1, J1/10, 0, J1/20
  at (0.1, 0.2, h)
  dof x y z rx ry rz
}
body b {
  mass 3
  inertia 1, 1, 1
  at (0, 0, 1)
  dof x y rz
}
spring s1 {
  from g at (0, 0, 0)
  to a at (0.5, 0.2, h)
  along (1, 2, 2)
  stiffness k1
  damping c1
}
spring s2 {
  from a at (0.1, 0.7, 0.3)
  to b at (0.1, 0, 1)
  along (1, 1, 0)
  stiffness k2
}
spring3 s3 {
  from g at (0, 1, 1)
  to a at (0.1, 1, h)
  stiffness k3, 2*k3, 3*k3
  damping c1, c1, c1
}
spring3 s4 {
  from g at (1, 0, 0)
  to a at (1, 0.2, h)
  stiffness k3, k3, k3
}
spring3 s5 {
  from g at (0, 0, 1)
  to b at (0.2, 0, 1)
  stiffness k3, k3, k3
}
torsion t1 {
  from a
  to b
  about (0, 1, 1)
  stiffness kt
  damping ct
}
input F force on a at (0.3, 0.2, h) along (0, 3, 4)
input T moment on b along z
output ya displacement of a at (0.1, 0.5, 0) along (1, 0, 1)
output yb acceleration of b at (1, 0, 1) along y
)", "oblique.mdl");
  compare_with_independent_assembly(model);
  // The oblique directions bring exact square roots, not floating-point numbers.
  const SymbolicModel sm = derive(model, {{}, false});
  const GiNaC::ex k2 = symbol_of(sm, "k2");
  // s2 joins a.x to b.x along (1, 1, 0)/sqrt(2): K(a.x, b.x) = -k2/2, exactly.
  CHECK(same(sm.K(0, 6), -k2 / 2));
  CHECK(sm.Ca(1, 7) == 1);  // yb: b.y along y
  CHECK(same(sm.Cd(0, 0), 1 / GiNaC::sqrt(GiNaC::ex(2))));
}
