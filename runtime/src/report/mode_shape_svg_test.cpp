// Mode shapes as SVG, on a hand-made geometry: a ground, body A at the origin (x and a rotation rz), body B at
// (1, 0, 0) (x), a spring from the ground to A and one from A's point (0.5, 0, 0) to B, a sensor on B along x.
// The points' motion is written here from u + theta x r, not taken from the code under test.
#include "mbgen/report/mode_shape_svg.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <regex>
#include <string>
#include <vector>

using namespace mbgen;

namespace {

ShapeGeometry two_bodies() {
  ShapeGeometry g;
  g.points = {{ShapePoint::Kind::Ground, "", {-1, 0, 0}},
              {ShapePoint::Kind::Body, "A", {0, 0, 0}},
              {ShapePoint::Kind::Body, "B", {1, 0, 0}},
              {ShapePoint::Kind::Attachment, "", {0.5, 0, 0}},
              {ShapePoint::Kind::Sensor, "dB", {1, 0, 0}}};
  g.lines = {{0, 1}, {3, 2}};
  g.sensors = {{"dB", 4, {1, 0, 0}}};
  // Coordinates: A.x, A.rz, B.x. Rows 3k..3k+2: point k's x, y, z.
  g.motion = Eigen::MatrixXd::Zero(15, 3);
  g.motion(3 * 1 + 0, 0) = 1;    // A's centre moves with A.x
  g.motion(3 * 2 + 0, 2) = 1;    // B's with B.x
  g.motion(3 * 3 + 0, 0) = 1;    // A's point (0.5, 0, 0): x with A.x,
  g.motion(3 * 3 + 1, 1) = 0.5;  // and y = (rz e_z x (0.5, 0, 0))_y = 0.5 rz
  g.motion(3 * 4 + 0, 2) = 1;    // the sensor on B
  return g;
}

struct Mark {
  double x, y;
};

// The centres of the circles of radius r and fill colour in the SVG, in the order written.
std::vector<Mark> circles(const std::string& svg, const std::string& r, const std::string& colour) {
  std::vector<Mark> out;
  const std::regex circle("<circle cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\" r=\"" + r + "\" fill=\"" + colour + "\"/>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator(); ++it)
    out.push_back({std::stod((*it)[1]), std::stod((*it)[2])});
  return out;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

const std::string grey = "#c8c8c8", red = "#d62728";

}  // namespace

TEST_CASE("a mode's picture has three views and its title", "[mode_shapes]") {
  const ShapeGeometry g = two_bodies();
  const std::vector<Eigen::VectorXcd> shapes = {Eigen::Vector3cd(1, 0, 0.4), Eigen::Vector3cd(0, 1, 0)};
  std::vector<std::string> pictures;
  for (std::size_t m = 0; m < shapes.size(); ++m)
    pictures.push_back(
        model_mode_svg(g, mode_title("mode " + std::to_string(m + 1), 90.8 + 60 * m, 0.005), shapes[m]));
  REQUIRE(pictures.size() == 2);
  for (std::size_t m = 0; m < pictures.size(); ++m) {
    const std::string& svg = pictures[m];
    CHECK(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0) == 0);
    CHECK(count(svg, "<svg") == 1);
    CHECK(count(svg, "</svg>") == 1);
    CHECK(count(svg, "<clipPath") == 3);
    for (const char* view : {">x-y (x to the right, y up)<", ">x-z (x to the right, z up)<",
                             ">y-z (y to the right, z up)<"})
      CHECK(count(svg, view) == 1);
    CHECK(count(svg, m == 0 ? "mode 1: 90.8 Hz, zeta 0.5 %" : "mode 2: 150.8 Hz, zeta 0.5 %") == 1);
    // Every number is finite: no nan or inf printed anywhere.
    CHECK(svg.find("nan") == std::string::npos);
    CHECK(svg.find("inf") == std::string::npos);
    // The ground's anchor: one hatched mark per view.
    CHECK(count(svg, "stroke=\"#777777\"") == 3);
  }
  CHECK(pictures[0] != pictures[1]);
}

TEST_CASE("a body moving in x is drawn displaced in x, not in y or z", "[mode_shapes]") {
  const ShapeGeometry g = two_bodies();
  const std::string svg = model_mode_svg(g, mode_title("mode 1", 100, 0.01), Eigen::Vector3cd(1, 0, 0.4));
  // Body marks (radius 4) in point order per view: A, B; views x-y, x-z, y-z.
  const std::vector<Mark> rest = circles(svg, "4.00", grey), moved = circles(svg, "4.00", red);
  REQUIRE(rest.size() == 6);
  REQUIRE(moved.size() == 6);
  for (int body = 0; body < 2; ++body) {
    const Mark& xy_rest = rest[static_cast<std::size_t>(body)];
    const Mark& xy_moved = moved[static_cast<std::size_t>(body)];
    CHECK(xy_moved.x > xy_rest.x + 1);  // to the right: +x
    CHECK(xy_moved.y == xy_rest.y);     // not up or down: no y
    const Mark& xz_rest = rest[2 + static_cast<std::size_t>(body)];
    const Mark& xz_moved = moved[2 + static_cast<std::size_t>(body)];
    CHECK(xz_moved.x > xz_rest.x + 1);
    CHECK(xz_moved.y == xz_rest.y);     // no z
    const Mark& yz_rest = rest[4 + static_cast<std::size_t>(body)];
    const Mark& yz_moved = moved[4 + static_cast<std::size_t>(body)];
    CHECK(yz_moved.x == yz_rest.x);     // the y-z view does not see x
    CHECK(yz_moved.y == yz_rest.y);
  }
  // A moves 1, B 0.4: A's mark moves 2.5 times as far (to the two decimals written).
  const double a = moved[0].x - rest[0].x, b = moved[1].x - rest[1].x;
  CHECK(a == Approx(2.5 * b).margin(0.03));
}

TEST_CASE("a rotation moves a point off its body's centre across the arm (u + theta x r)", "[mode_shapes]") {
  const ShapeGeometry g = two_bodies();
  const std::string svg = model_mode_svg(g, mode_title("mode 1", 100, 0.01), Eigen::Vector3cd(0, 1, 0));
  // Attachment marks (radius 2): one point, three views. A rotation about z moves (0.5, 0, 0) along +y.
  const std::vector<Mark> rest = circles(svg, "2.00", grey), moved = circles(svg, "2.00", red);
  REQUIRE(rest.size() == 3);
  REQUIRE(moved.size() == 3);
  CHECK(moved[0].x == rest[0].x);
  CHECK(moved[0].y < rest[0].y - 1);  // up in the x-y view (SVG's y grows downwards)
  CHECK(moved[2].x > rest[2].x + 1);  // to the right in the y-z view
  // The bodies' centres do not move.
  const std::vector<Mark> bodies_rest = circles(svg, "4.00", grey), bodies_moved = circles(svg, "4.00", red);
  REQUIRE(bodies_moved.size() == 6);
  for (std::size_t k = 0; k < 6; ++k) {
    CHECK(bodies_moved[k].x == bodies_rest[k].x);
    CHECK(bodies_moved[k].y == bodies_rest[k].y);
  }
}

TEST_CASE("the same shape gives the same bytes, whatever its complex phase", "[mode_shapes]") {
  const ShapeGeometry g = two_bodies();
  const Eigen::VectorXcd shape = Eigen::Vector3cd(1, 0.2, -0.7);
  const std::string first = model_mode_svg(g, mode_title("mode 3", 123.456, 0.02), shape);
  CHECK(model_mode_svg(g, mode_title("mode 3", 123.456, 0.02), shape) == first);
  CHECK(model_mode_svg(g, mode_title("mode 3", 123.456, 0.02), shape * std::polar(2.0, 0.9)) == first);
  // The largest translation is real and positive after the turn, whatever the eigenvector's phase.
  const Eigen::Matrix3Xd d = point_displacements(g, shape * std::complex<double>(0, -1));
  CHECK(d(0, 1) == Approx(1));
  CHECK(d(0, 2) == Approx(-0.7));
}

TEST_CASE("a shape known at the sensors moves only the sensor points", "[mode_shapes]") {
  const ShapeGeometry g = two_bodies();
  SensorShape measured;
  measured.sensor = {0};
  measured.value = Eigen::VectorXcd::Constant(1, std::complex<double>(0, -2));
  std::vector<bool> shown;
  const Eigen::Matrix3Xcd translations = sensor_translations(g, measured, shown);
  const Eigen::Matrix3Xd d = real_at_peak(translations, translations);
  CHECK(shown == std::vector<bool>{false, false, false, false, true});
  CHECK(d(0, 4) == Approx(2));
  CHECK(d.leftCols(4).isZero());
  ShapeLayer layer;
  layer.displacement = d;
  layer.points = shown;
  layer.lines = false;
  layer.arrows = true;
  layer.colour = "#1f77b4";
  layer.legend = "measured <at the sensors>";
  const std::string svg = mode_shape_svg(g, {layer}, "mode 1 & more");
  CHECK(count(svg, "<rect x=") >= 3);
  CHECK(svg.find("measured &lt;at the sensors&gt;") != std::string::npos);
  CHECK(svg.find("mode 1 &amp; more") != std::string::npos);
  CHECK(count(svg, "stroke=\"#1f77b4\" stroke-width=\"1.5\"/>") == 3);  // the sensor's square, once per view
  CHECK(count(svg, "stroke-dasharray") == 3);                           // its arrow, once per view
}

TEST_CASE("a mode that moves none of the drawn points says so", "[mode_shapes]") {
  ShapeGeometry g = two_bodies();
  g.motion.setZero();
  const std::string svg = model_mode_svg(g, mode_title("mode 1", 10, 0.01), Eigen::Vector3cd(1, 1, 1));
  CHECK(svg.find("do not move") != std::string::npos);
  CHECK(svg.find("nan") == std::string::npos);
}
