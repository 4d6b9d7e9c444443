// Models the derivation must reject: each error names the file, line and column of the offending node.
#include <catch2/catch.hpp>

#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"

using namespace mbgen;
using namespace mbgen::symbolic;

namespace {

std::string derive_error(const std::string& text, const DeriveOptions& options = {}) {
  const ir::ModelIr model = frontend::parse_string(text, "t.mdl");
  try {
    derive(model, options);
  } catch (const frontend::ModelError& e) {
    return e.what();
  }
  return "no error";
}

// One rigid body `a` on four springs; `extra` goes into its body block, `dofs` are its coordinates.
std::string one_body(const std::string& dofs, const std::string& inertia, const std::string& more = "") {
  return "model t\n"                                      // 1
         "param m = 2\n"                                  // 2
         "param k = 1000\n"                               // 3
         "ground g\n"                                     // 4
         "body a {\n"                                     // 5
         "  mass m\n"                                     // 6
         "  " + inertia + "\n"                            // 7
         "  dof " + dofs + "\n"                           // 8
         "}\n"                                            // 9
         "spring3 s1 {\n  from g at (1, 0, 0)\n  to a at (1, 0, 0)\n  stiffness k, k, k\n}\n"      // 10-14
         "spring3 s2 {\n  from g at (0, 1, 0)\n  to a at (0, 1, 0)\n  stiffness k, k, k\n}\n"      // 15-19
         "spring3 s3 {\n  from g at (0, 0, 1)\n  to a at (0, 0, 1)\n  stiffness k, k, k\n}\n" +    // 20-24
         more;
}

}  // namespace

TEST_CASE("a well-posed rigid body on three 3-D springs derives") {
  CHECK(derive_error(one_body("x y z rx ry rz", "inertia 1, 2, 3")) == "no error");
}

TEST_CASE("a coordinate with zero inertia is rejected at its body") {
  CHECK(derive_error(one_body("x rx", "inertia 0, 2, 3")) ==
        "t.mdl:5:6: error: coordinate a.rx has zero inertia about x at the current parameter values (singular mass "
        "matrix); give body `a` a non-zero inertia (inertia XX, YY, ZZ), or remove rx from its dof list");
  // An absent inertia statement means zero inertia.
  CHECK(derive_error(one_body("x ry", "")).find("t.mdl:5:6: error: coordinate a.ry has zero inertia about y") == 0);
}

TEST_CASE("a coordinate with zero mass at the current values is rejected") {
  DeriveOptions o;
  o.set["m"] = "0";
  CHECK(derive_error(one_body("x y", "inertia 1, 1, 1"), o) ==
        "t.mdl:5:6: error: coordinate a.x has zero mass at the current parameter values (singular mass matrix); "
        "give body `a` a non-zero mass, or remove x from its dof list");
}

TEST_CASE("a singular inertia tensor is rejected at its body") {
  // Jxx = Jyy = Jxy = 1: the tensor restricted to rx, ry is [[1, 1], [1, 1]], singular with non-zero diagonal.
  CHECK(derive_error(one_body("rx ry", "inertia 1, 1, 1, 1, 0, 0")) ==
        "t.mdl:5:6: error: the mass matrix of body `a` is singular at the current parameter values (its inertia "
        "tensor is not positive definite on its rotation coordinates); check its inertia values");
}

TEST_CASE("a coordinate no element acts on is rejected with its body and dof") {
  const std::string text =
      "model t\nparam k = 1000\nground g\n"
      "body a {\n  mass 1\n  dof x y\n}\n"
      "spring s {\n  from g\n  to a\n  along x\n  stiffness k\n}\n";
  CHECK(derive_error(text) ==
        "t.mdl:4:6: error: coordinate a.y: no element acts on it (its stiffness and damping rows are zero); attach "
        "an element to body `a` that resists y, or remove y from its dof list");
  // A spring through the centre of mass does not hold the rotation about its line of action.
  const std::string through_centre =
      "model t\nparam k = 1000\nground g\n"
      "body a {\n  mass 1\n  inertia 1, 1, 1\n  dof x rz\n}\n"
      "spring s {\n  from g at (-1, 0, 0)\n  to a\n  along x\n  stiffness k\n}\n";
  CHECK(derive_error(through_centre).find("t.mdl:4:6: error: coordinate a.rz: no element acts on it") == 0);
}

TEST_CASE("a spin about an axis that is not an axis of symmetry is rejected at the spin") {
  CHECK(derive_error(one_body("x y z rx ry", "inertia 1, 2, 3", "spin a about z speed 10\n")) ==
        "t.mdl:25:6: error: body `a` cannot spin about z: its transverse inertias Jxx and Jyy differ (as "
        "expressions); a spin needs a principal axis with equal transverse inertias (products of inertia zero, "
        "Jxx = Jyy)");
  CHECK(derive_error(one_body("x y z rx ry", "inertia 1, 1, 3, 0, 0.5, 0", "spin a about z speed 10\n")) ==
        "t.mdl:25:6: error: body `a` cannot spin about z: its product of inertia Jxz is not zero; a spin needs a "
        "principal axis with equal transverse inertias (products of inertia zero, Jxx = Jyy)");
  CHECK(derive_error(one_body("x y z rx ry", "inertia 1, 3, 3", "spin a about x speed 10\n")) == "no error");
}

TEST_CASE("a model without inputs and outputs derives, with empty B and output matrices") {
  const ir::ModelIr model = frontend::parse_string(
      "model z\nparam k = 1\nground g\nbody a {\n  mass 1\n  dof x\n}\n"
      "spring s {\n  from g\n  to a\n  along x\n  stiffness k\n}\n", "z.mdl");
  const SymbolicModel sm = derive(model);
  CHECK(sm.B.rows() == 1);
  CHECK(sm.B.cols() == 0);
  CHECK(sm.Cd.rows() == 0);
  CHECK(sm.transfer_functions.empty());
  CHECK(sm.K(0, 0) == sm.parameters[0].sym);
}
