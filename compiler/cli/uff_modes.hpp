// Modes as UFF datasets 55 (a shape per mode at nodes and directions) with the nodes' coordinates as dataset 15 and
// trace lines between them as datasets 82:
// the model's sensor points (`mbgen export --what modes --format uff`) and the points of measured FRFs
// (`mbgen modal --uff`). Layout: runtime/include/mbgen/data/uff55.hpp; what is written: docs/data.md.
#pragma once

#include <mbgen/modal_identification/modal_identification.hpp>
#include <mbgen/data/uff55.hpp>

#include <Eigen/Core>

#include <complex>
#include <map>
#include <string>
#include <vector>

#include "ir/model_ir.hpp"

namespace mbgen::cli {

// A measurement point: a node and a direction (1..6 = +X, +Y, +Z, +RX, +RY, +RZ; negative for the opposite).
struct UffPoint {
  int node = 0;
  int direction = 0;
};

// The model's outputs as UFF points: one node per distinct place (frame and point) that an output measures, numbered
// from 1 in the order of the outputs, at its global coordinates (parameter values from `values`, the model's own
// where absent); the direction is the output's axis. DataError (model file, line, column) for an output whose
// direction is not along a global axis: dataset 55 holds X, Y and Z.
// The trace lines draw the structure on these nodes as the model's elements connect its bodies: the nodes on one
// body in a chain (node order), and for each element between two bodies that both carry nodes, a line from the node
// of one body nearest to the element's end there to the node of the other nearest to its other end. An element to a
// ground, or to a body with no sensor point, draws no line (a node is only where a shape value is).
struct SensorGeometry {
  std::map<std::string, UffPoint> outputs;  // output name -> point
  std::vector<Uff15Node> nodes;             // ascending node numbers
  std::vector<Uff82TraceLine> traces;       // one per line, two nodes each, numbered from 1; pairs ascending
};
SensorGeometry sensor_geometry(const ir::ModelIr& model, const std::map<std::string, double>& values);

// "12:+X" (uff_point_key's text) as a point; false for other text.
bool parse_uff_point_key(const std::string& key, UffPoint& point);

// Mode shapes at points (rows: points, columns: modes) with their eigenvalues (rad/s) as datasets 55: complex modes
// (analysis type 3), three translations per node, or six when a point is a rotation (values at directions not
// measured are 0), the nodes ascending; a point measured along -X gives X the opposite sign. Of two points at one node and direction, the first one's value
// is written. `nodes`, if not empty, go first as a dataset 15 (only those the points use). `specific_data_type`:
// 8 displacement, 11 velocity, 12 acceleration (0 unknown). `id` becomes ID lines 1 and 2 of every mode. `traces`
// follow the dataset 15 as datasets 82, those whose nodes are all among the points' (with the 15 written).
std::string uff55_modes_text(const std::vector<UffPoint>& points, const std::vector<std::complex<double>>& eigenvalues,
                             const Eigen::MatrixXcd& shapes, int specific_data_type, const std::string& id1,
                             const std::string& id2, const std::vector<Uff15Node>& nodes,
                             const std::vector<Uff82TraceLine>& traces = {});

// The mapping file beside UFF modes (`OUT.map`): which model output or measured channel each point is.
std::string uff_points_mapping(const std::string& title, const std::vector<std::string>& names,
                               const std::vector<UffPoint>& points);

// A UFF file and the mapping file beside it.
struct UffText {
  std::string data, mapping;
};

// The modes `modal` identified, as UFF 55 (modal_uff.cpp): each shape is the residue column of one reference input
// (the input with the most channels, the first on a tie) at the outputs measured with it, as in the JSON's "shape".
// An output's point: its name when it is one ("node12:+Z", a UFF file read without a mapping), the mapping file
// beside its data file (FILE.map) that named it, or else, when every output is one of the model's, the model's
// sensor points (sensor_geometry). Nodes come with their UFF 15 coordinates and UFF 82 trace lines from the model or
// from datasets 15 and 82 in the data files; `sets` (--set) place them. DataError (first data file) naming an output
// that none of these places.
UffText identified_modes_uff(const ModalData& data, const ModalIdentification& result,
                             const std::vector<std::string>& data_paths, const ir::ModelIr* model,
                             const std::map<std::string, std::string>& sets);

}  // namespace mbgen::cli
