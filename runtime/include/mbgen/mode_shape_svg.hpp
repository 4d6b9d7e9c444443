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

// The translations of the sensor points from a shape known at the outputs only: value[s] (complex, one per
// sensor; NaN or a sensor index not in `sensors` leaves it out) along sensors[s].direction, summed per point,
// with the same phase rule as point_displacements. Points that no given sensor measures stay at rest and are not
// marked as measured.
struct SensorShape {
  std::vector<int> sensor;                     // indices into ShapeGeometry::sensors
  Eigen::VectorXcd value;                      // one per entry of `sensor`
};
Eigen::Matrix3Xd sensor_displacements(const ShapeGeometry& geometry, const SensorShape& shape,
                                      std::vector<bool>& measured);

// One deformed shape drawn over the undeformed geometry.
struct ShapeLayer {
  Eigen::Matrix3Xd displacement;  // 3 x points
  std::vector<bool> points;       // which points this layer draws (all when empty)
  bool lines = true;              // draw the elements whose two ends it draws
  bool arrows = false;            // a thin line from each drawn point's rest position to its displaced one
  std::string colour = "#d62728";
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

// A model's mode on its whole geometry: the picture titled "mode NUMBER: F Hz, zeta Z %".
std::string model_mode_svg(const ShapeGeometry& geometry, int number, double f_hz, double zeta,
                           const Eigen::VectorXcd& shape);

// The title of mode `number` at f_hz and zeta, as the pictures write it.
std::string mode_title(int number, double f_hz, double zeta);

}  // namespace mbgen
