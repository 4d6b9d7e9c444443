// The geometry mode shapes are drawn on, from a model file: its points where the file puts them, and each point's
// translation per unit coordinate as u + theta x r written out here by hand.
#include "evaluator/shape_geometry.hpp"

#include <catch2/catch.hpp>

#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"

using namespace mbgen;

namespace {

const char* const kModel = R"(model arm
param m = 2
param J = 0.1
param k = 1e5
param a = 0.5
ground base
body A {
  mass m
  inertia J, J, J
  at (1, 2, 3)
  dof x y z rx ry rz
}
body B {
  mass m
  at (3, 2, 3)
  dof x
}
spring3 mount {
  from base at (1, 2, 0)
  to A
  stiffness k, k, k
}
spring link {
  from A at (1 + a, 2, 3.25)
  to B
  along x
  stiffness k
}
output dA_x displacement of A at (1 + a, 2, 3.25) along x
output dA_z displacement of A at (1 + a, 2, 3.25) along (0, 0, 2)
output dB displacement of B along x
)";

int find(const ShapeGeometry& g, ShapePoint::Kind kind, const Eigen::Vector3d& at) {
  for (std::size_t k = 0; k < g.points.size(); ++k)
    if (g.points[k].kind == kind && (g.points[k].position - at).norm() < 1e-12) return static_cast<int>(k);
  return -1;
}

}  // namespace

TEST_CASE("shape geometry: points, elements, sensors and u + theta x r", "[shape_geometry]") {
  const ir::ModelIr model = frontend::parse_string(kModel, "arm.mdl");
  const ShapeGeometry g = evaluator::shape_geometry(model);
  // A's centre, B's centre, the ground's end, A's arm point (the link's end and the sensors' place).
  const int a = find(g, ShapePoint::Kind::Body, {1, 2, 3}), b = find(g, ShapePoint::Kind::Body, {3, 2, 3});
  const int ground = find(g, ShapePoint::Kind::Ground, {1, 2, 0});
  const int arm = find(g, ShapePoint::Kind::Attachment, {1.5, 2, 3.25});
  const int sensor = find(g, ShapePoint::Kind::Sensor, {1.5, 2, 3.25});
  REQUIRE(a >= 0);
  REQUIRE(b >= 0);
  REQUIRE(ground >= 0);
  REQUIRE(arm >= 0);
  REQUIRE(sensor >= 0);
  CHECK(g.points[static_cast<std::size_t>(a)].label == "A");
  // The mount's end on A is A's centre and the link's end on B is B's; dB's sensor at B's centre is a point of its
  // own (drawn as a square around the body's mark).
  CHECK(g.points.size() == 6);
  CHECK(g.lines == std::vector<std::pair<int, int>>{{ground, a}, {arm, b}});
  REQUIRE(g.sensors.size() == 3);
  CHECK(g.sensors[0].point == sensor);
  CHECK(g.sensors[1].point == sensor);  // two outputs at one place share its point
  CHECK(g.sensors[2].point == find(g, ShapePoint::Kind::Sensor, {3, 2, 3}));
  CHECK((g.sensors[1].direction - Eigen::Vector3d(0, 0, 1)).norm() < 1e-15);

  // Coordinates A.x y z rx ry rz, B.x. The arm r = (0.5, 0, 0.25) from A's centre:
  // theta x r = (0.25 ry, 0.5 rz - 0.25 rx, -0.5 ry).
  REQUIRE(g.motion.rows() == 3 * static_cast<Eigen::Index>(g.points.size()));
  REQUIRE(g.motion.cols() == 7);
  Eigen::MatrixXd expected(3, 7);
  expected << 1, 0, 0, 0, 0.25, 0, 0,
              0, 1, 0, -0.25, 0, 0.5, 0,
              0, 0, 1, 0, -0.5, 0, 0;
  CHECK((g.motion.middleRows(3 * arm, 3) - expected).norm() < 1e-12);
  CHECK((g.motion.middleRows(3 * sensor, 3) - expected).norm() < 1e-12);
  Eigen::MatrixXd centre = Eigen::MatrixXd::Zero(3, 7);
  centre.leftCols(3).setIdentity();
  CHECK((g.motion.middleRows(3 * a, 3) - centre).norm() < 1e-12);
  CHECK(g.motion.middleRows(3 * ground, 3).isZero());
  Eigen::MatrixXd b_moves = Eigen::MatrixXd::Zero(3, 7);
  b_moves(0, 6) = 1;
  CHECK((g.motion.middleRows(3 * b, 3) - b_moves).norm() < 1e-12);
}

TEST_CASE("shape geometry: --set moves the points", "[shape_geometry]") {
  const ir::ModelIr model = frontend::parse_string(kModel, "arm.mdl");
  const ShapeGeometry g = evaluator::shape_geometry(model, {{"a", "1"}});
  const int arm = find(g, ShapePoint::Kind::Attachment, {2, 2, 3.25});
  REQUIRE(arm >= 0);
  CHECK(g.motion(3 * arm + 1, 5) == Approx(1));  // y per rz: the arm is now 1 long
  CHECK_THROWS_AS(evaluator::shape_geometry(model, {{"nope", "1"}}), frontend::ModelError);
}
