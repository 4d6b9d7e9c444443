// `mbgen modal --uff OUT.uff`: the identified modes at the measured points (compiler/cli/uff_modes.hpp).
#include <mbgen/data/data_error.hpp>
#include <mbgen/data/uff.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>

#include "cli/frf_uff58.hpp"
#include "cli/uff_modes.hpp"

namespace mbgen::cli {

namespace {

// Points named by the data themselves: "node12:+Z", or a mapping file beside a data file.
bool point_from_data(const std::string& name, const std::vector<UffMapping>& mappings, UffPoint& point) {
  if (name.rfind("node", 0) == 0 && parse_uff_point_key(name.substr(4), point)) return true;
  for (const UffMapping& mapping : mappings)
    for (const auto& [key, mapped] : mapping.names)
      if (mapped == name && parse_uff_point_key(key, point)) return true;
  return false;
}

}  // namespace

UffText identified_modes_uff(const ModalData& data, const ModalIdentification& result,
                             const std::vector<std::string>& data_paths, const ir::ModelIr* model,
                             const std::map<std::string, std::string>& sets) {
  if (result.modes.empty()) throw DataError(data_paths.front(), 0, 0, "--uff: no mode was identified to write");
  // The reference: the input with the most channels.
  std::vector<int> count(data.inputs.size(), 0);
  for (const ModalData::Channel& c : data.channels) ++count[static_cast<std::size_t>(c.input)];
  const int reference = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());

  std::vector<UffMapping> mappings;
  std::vector<Uff15Node> nodes;
  std::vector<Uff82TraceLine> traces;  // the data's geometry, kept: written with the modes
  for (const std::string& path : data_paths) {
    if (path == "-") continue;
    if (std::filesystem::exists(path + ".map")) mappings.push_back(read_uff_mapping(path + ".map"));
    std::ifstream in(path, std::ios::binary);
    try {
      for (const Uff15Node& n : read_uff15(in, path)) nodes.push_back(n);
      in.clear();
      in.seekg(0);
      for (Uff82TraceLine& t : read_uff82(in, path)) traces.push_back(std::move(t));
    } catch (const DataError&) {
      // Read as data already: a CSV file, which holds no nodes.
    }
  }

  std::vector<std::size_t> channels;  // of the reference, in output order
  std::vector<std::string> names;
  for (std::size_t c = 0; c < data.channels.size(); ++c)
    if (data.channels[c].input == reference) {
      channels.push_back(c);
      names.push_back(data.outputs[static_cast<std::size_t>(data.channels[c].output)]);
    }
  std::vector<UffPoint> points(names.size());
  bool from_data = true;
  std::string unplaced;
  for (std::size_t k = 0; k < names.size() && from_data; ++k)
    if (!point_from_data(names[k], mappings, points[k])) {
      from_data = false;
      unplaced = names[k];
    }
  if (!from_data) {
    std::optional<SensorGeometry> geometry;
    std::map<std::string, double> values;
    for (const auto& [name, text] : sets) values[name] = std::stod(text);  // checked by parse_set_options
    if (model) geometry = sensor_geometry(*model, values);
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (!geometry || !geometry->outputs.count(names[k]))
        throw DataError(data_paths.front(), 0, 0,
                        "--uff: the output `" + (geometry ? names[k] : unplaced) +
                            "` has no UFF node and direction: name it in a mapping file beside its data file "
                            "(FILE.map, e.g. `12:+Z = " + (geometry ? names[k] : unplaced) +
                            "`) or give --model with it as an output");
      points[k] = geometry->outputs.at(names[k]);
    }
    nodes = geometry->nodes;
    traces = geometry->traces;
  }

  Eigen::MatrixXcd shapes(static_cast<Eigen::Index>(channels.size()), static_cast<Eigen::Index>(result.modes.size()));
  std::vector<std::complex<double>> eigenvalues;
  for (std::size_t m = 0; m < result.modes.size(); ++m) {
    eigenvalues.push_back(result.modes[m].lambda);
    for (std::size_t k = 0; k < channels.size(); ++k)
      shapes(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(m)) =
          result.modes[m].residues[static_cast<Eigen::Index>(channels[k])];
  }
  const std::string& input = data.inputs[static_cast<std::size_t>(reference)];
  UffText out;
  out.data = uff55_modes_text(points, eigenvalues, shapes, uff_specific_data_type(data.quantity), "mbgen modal",
                              "residues of reference " + input, nodes, traces);
  out.mapping = uff_points_mapping("mbgen modal", names, points);
  return out;
}

}  // namespace mbgen::cli
