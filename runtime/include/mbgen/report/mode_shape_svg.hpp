// Mode shapes drawn on a model's geometry, as small self-contained SVG pictures for the reports of `modal --model`
// and `sensitivity` (docs/modal.md, docs/sensitivity.md): the bodies' centres of mass, the sensor points and the
// elements' attachment points, the elements as lines between their ends (an end on a ground as a hatched anchor),
// undeformed in light grey and deformed in colour, in three orthographic views (x-y, x-z, y-z) side by side.
//
// The geometry is plain numbers: where the points are and how each moves with the model's generalized coordinates
// (the linearized u + theta x r of its body). The command builds it from the model file (compiler/cli/
// shape_geometry.hpp); this part only draws, the same bytes for the same input.
#pragma once

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace mbgen {

struct ShapePoint {
  enum class Kind {
    Body,        // a body's centre of mass
    Sensor,      // where an output measures
    Attachment,  // an element's end on a body
    Ground,      // an element's end on a ground: never moves, drawn as a hatched anchor
  };
  Kind kind = Kind::Body;
  std::string label;          // the body's or output's name; empty for attachment and ground points
  Eigen::Vector3d position;   // global, nominal configuration
};

// An output's direction at its sensor point, for shapes known only at the sensors (measured ones).
struct ShapeSensor {
  std::string output;
  int point = 0;              // index into ShapeGeometry::points
  Eigen::Vector3d direction;  // unit vector, global
};

struct ShapeGeometry {
  std::vector<ShapePoint> points;
  std::vector<std::pair<int, int>> lines;  // elements, as indices of their two end points
  std::vector<ShapeSensor> sensors;        // one per output
  // Rows 3k, 3k + 1, 3k + 2: the translation (x, y, z) of point k per unit of each of the model's body coordinates
  // (columns, in the model's coordinate order; filter states, which move nothing, come after them and are not here).
  Eigen::MatrixXd motion;
};

// A mode's translations of every point (3 x points), real: the complex displacements motion * shape turned by one
// common phase so that the largest of them is real and positive, then their real parts (the deformed shape at the
// instant that component peaks). Entries of `shape` past motion.cols() are ignored.
Eigen::Matrix3Xd point_displacements(const ShapeGeometry& geometry, const Eigen::VectorXcd& shape);

// A shape known at the outputs only (a measured one): value[s] at sensor `sensor[s]` (an index into
// ShapeGeometry::sensors), complex.
struct SensorShape {
  std::vector<int> sensor;
  Eigen::VectorXcd value;  // one per entry of `sensor`
};

// Its complex translations of the points (3 x points): each value along its sensor's direction, summed per point.
// A non-finite value or a sensor index out of range is left out. `measured` tells which points a value moved.
Eigen::Matrix3Xcd sensor_translations(const ShapeGeometry& geometry, const SensorShape& shape,
                                      std::vector<bool>& measured);

// Complex translations made real: turned by the one phase that makes the largest entry of `reference` real and
// positive, then their real parts. Two shapes turned by the same reference compare at the same instant.
Eigen::Matrix3Xd real_at_peak(const Eigen::Matrix3Xcd& translations, const Eigen::Matrix3Xcd& reference);

// One deformed shape drawn over the undeformed geometry.
struct ShapeLayer {
  Eigen::Matrix3Xd displacement;  // 3 x points
  std::vector<bool> points;       // which points this layer draws (all when empty)
  bool lines = true;              // draw the elements whose two ends it draws
  bool arrows = false;            // a thin line from each drawn point's rest position to its displaced one
  std::string colour = "#d62728";
  double marker = 1;              // size of its point marks (a larger one stays visible under a later layer's)
  std::string legend;             // a line of the caption; empty for none
};

// The largest displacement over all layers is drawn as `kShapeFraction` of the model's size (the largest extent of
// its points' bounding box; 1 when every point sits at one place), the layers with one common factor so that they
// compare. Views share one scale, each centred on what it shows.
inline constexpr double kShapeFraction = 0.2;

// The SVG text: a title line (e.g. "mode 2: 153.801 Hz, zeta 0.474 %"), the three views, the layers' legends.
// Names are escaped; coordinates are written with two decimals, so the same input gives the same bytes.
std::string mode_shape_svg(const ShapeGeometry& geometry, const std::vector<ShapeLayer>& layers,
                           const std::string& title);

// A model's mode (`shape` over its coordinates) drawn on its whole geometry, in red.
std::string model_mode_svg(const ShapeGeometry& geometry, const std::string& title, const Eigen::VectorXcd& shape);

// A picture's title: "NAME: F Hz, zeta Z %" (6 and 4 significant digits).
std::string mode_title(const std::string& name, double f_hz, double zeta);

}  // namespace mbgen
