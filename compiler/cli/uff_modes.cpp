#include "cli/uff_modes.hpp"

#include <mbgen/data/data_error.hpp>
#include <mbgen/data/uff.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "diagnosis/model_values.hpp"

namespace mbgen::cli {

namespace {

// The axis (1, 2, 3; negative when opposite) a direction lies along, or 0.
int axis_of(const ir::Direction& d, const diagnosis::ModelValues& values) {
  if (d.axis == "x") return 1;
  if (d.axis == "y") return 2;
  if (d.axis == "z") return 3;
  const double v[3] = {values.of(d.vector[0]), values.of(d.vector[1]), values.of(d.vector[2])};
  const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int k = 0; k < 3; ++k)
    if (norm > 0 && std::abs(std::abs(v[k]) - norm) <= 1e-12 * norm) return v[k] > 0 ? k + 1 : -(k + 1);
  return 0;
}

}  // namespace

SensorGeometry sensor_geometry(const ir::ModelIr& model, const std::map<std::string, double>& overrides) {
  const diagnosis::ModelValues values(model, overrides);
  SensorGeometry g;
  std::vector<std::pair<std::string, std::array<double, 3>>> places;  // (frame, point) of each node, node = index + 1
  for (const ir::Output& out : model.outputs) {
    const int axis = axis_of(out.direction, values);
    if (axis == 0)
      throw DataError(model.file, out.direction.loc.line ? out.direction.loc.line : out.loc.line,
                      out.direction.loc.line ? out.direction.loc.column : out.loc.column,
                      "output `" + out.name +
                          "` measures along a direction that is not a global axis: UFF dataset 55 holds X, Y and Z "
                          "components only");
    const std::array<double, 3> xyz = {values.of(out.at.point[0]), values.of(out.at.point[1]),
                                       values.of(out.at.point[2])};
    std::size_t k = 0;
    while (k < places.size() && !(places[k].first == out.at.frame && places[k].second == xyz)) ++k;
    if (k == places.size()) places.emplace_back(out.at.frame, xyz);
    g.outputs[out.name] = {static_cast<int>(k) + 1, axis};
  }
  for (std::size_t k = 0; k < places.size(); ++k) {
    Uff15Node n;
    n.node = static_cast<int>(k) + 1;
    n.xyz = places[k].second;
    g.nodes.push_back(n);
  }
  // The lines: node pairs (ascending, each once) on one body, then across the elements between bodies.
  std::set<std::pair<int, int>> lines;
  const auto add = [&](std::size_t a, std::size_t b) {
    if (a != b) lines.insert({static_cast<int>(std::min(a, b)) + 1, static_cast<int>(std::max(a, b)) + 1});
  };
  for (std::size_t k = 0; k < places.size(); ++k)
    for (std::size_t next = k + 1; next < places.size(); ++next)
      if (places[next].first == places[k].first) {
        add(k, next);
        break;
      }
  // The node on `frame` nearest to the point `at`; places.size() when the frame has none.
  const auto nearest = [&](const ir::Attachment& at) {
    const std::array<double, 3> xyz = {values.of(at.point[0]), values.of(at.point[1]), values.of(at.point[2])};
    std::size_t best = places.size();
    double best_distance = 0;
    for (std::size_t k = 0; k < places.size(); ++k) {
      if (places[k].first != at.frame) continue;
      double d = 0;
      for (int i = 0; i < 3; ++i) d += (places[k].second[i] - xyz[i]) * (places[k].second[i] - xyz[i]);
      if (best == places.size() || d < best_distance) best = k, best_distance = d;
    }
    return best;
  };
  for (const ir::Element& e : model.elements) {
    if (model.is_ground(e.a.frame) || model.is_ground(e.b.frame)) continue;
    const std::size_t a = nearest(e.a), b = nearest(e.b);
    if (a < places.size() && b < places.size()) add(a, b);
  }
  for (const auto& [a, b] : lines) {
    Uff82TraceLine t;
    t.number = static_cast<int>(g.traces.size()) + 1;
    t.id = "mbgen: the model's structure";
    t.nodes = {a, b};
    g.traces.push_back(std::move(t));
  }
  return g;
}

bool parse_uff_point_key(const std::string& key, UffPoint& point) {
  const std::size_t colon = key.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  int node = 0;
  for (std::size_t i = 0; i < colon; ++i) {
    if (key[i] < '0' || key[i] > '9' || node > 100000000) return false;
    node = node * 10 + (key[i] - '0');
  }
  const std::string dir = key.substr(colon + 1);
  for (int d = -6; d <= 6; ++d)
    if (uff_direction_name(d) == dir) {
      point = {node, d};
      return true;
    }
  return false;
}

std::string uff55_modes_text(const std::vector<UffPoint>& points, const std::vector<std::complex<double>>& eigenvalues,
                             const Eigen::MatrixXcd& shapes, int specific_data_type, const std::string& id1,
                             const std::string& id2, const std::vector<Uff15Node>& nodes,
                             const std::vector<Uff82TraceLine>& traces) {
  std::set<int> used;
  for (const UffPoint& p : points) used.insert(p.node);
  std::ostringstream out;
  std::vector<Uff15Node> geometry;
  for (const Uff15Node& n : nodes)
    if (used.count(n.node)) geometry.push_back(n);
  if (!geometry.empty()) {
    write_uff15(out, geometry);
    std::set<int> placed;
    for (const Uff15Node& n : geometry) placed.insert(n.node);
    for (const Uff82TraceLine& t : traces)
      if (std::all_of(t.nodes.begin(), t.nodes.end(), [&](int n) { return n == 0 || placed.count(n); }))
        write_uff82(out, t);
  }
  const std::vector<int> node_list(used.begin(), used.end());
  // Rotations measured (directions 4 to 6): six values per node, else the three translations.
  const bool six = std::any_of(points.begin(), points.end(), [](const UffPoint& p) { return std::abs(p.direction) > 3; });
  for (std::size_t m = 0; m < eigenvalues.size(); ++m) {
    Uff55Record r;
    r.id = {id1, id2, "NONE", "NONE", "NONE"};
    r.analysis_type = 3;
    r.data_characteristic = six ? 3 : 2;
    r.specific_data_type = specific_data_type;
    r.complex = true;
    r.mode_number = static_cast<int>(m) + 1;
    r.eigenvalue = eigenvalues[m];
    r.nodes = node_list;
    r.values = Eigen::MatrixXcd::Zero(static_cast<Eigen::Index>(node_list.size()), six ? 6 : 3);
    std::set<std::pair<int, int>> written;
    for (std::size_t p = 0; p < points.size(); ++p) {
      const int axis = std::abs(points[p].direction);
      if (axis < 1 || axis > 6 || !written.insert({points[p].node, axis}).second) continue;
      const auto row = std::lower_bound(node_list.begin(), node_list.end(), points[p].node) - node_list.begin();
      const std::complex<double> v = shapes(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(m));
      r.values(row, axis - 1) = points[p].direction > 0 ? v : -v;
    }
    write_uff55(out, r);
  }
  return out.str();
}

std::string uff_points_mapping(const std::string& title, const std::vector<std::string>& names,
                               const std::vector<UffPoint>& points) {
  std::string text = "# " + title + ": UFF points to channels\n";
  for (std::size_t i = 0; i < names.size(); ++i)
    text += uff_point_key(points[i].node, points[i].direction) + " = " + names[i] + "\n";
  return text;
}

}  // namespace mbgen::cli
