// Measured shapes drawn on the model's sensor geometry: the residues of the reference input's channels, each along
// its output's direction at its sensor point, beside the paired model mode's residues at the same channels (turned
// and scaled by the one complex factor that fits them best to the measured ones, so that the two compare) and the
// model mode on the whole geometry.
#include "modal_shape_figures.hpp"

#include "mbgen/report/mode_shape_figures.hpp"
#include "mbgen/report/mode_shape_svg.hpp"
#include "mbgen/report/report_files.hpp"

#include <algorithm>
#include <filesystem>
#include <set>

namespace mbgen {

namespace {

const char* const kMeasuredColour = "#1f77b4";
const char* const kModelColour = "#d62728";

// The input with the most channels (the first on a tie), as the UFF export of identified modes chooses it.
int reference_input(const ModalData& data) {
  std::vector<int> count(data.inputs.size(), 0);
  for (const ModalData::Channel& c : data.channels) ++count[static_cast<std::size_t>(c.input)];
  return static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
}

int sensor_of(const ShapeGeometry& g, const std::string& output) {
  for (std::size_t s = 0; s < g.sensors.size(); ++s)
    if (g.sensors[s].output == output) return static_cast<int>(s);
  return -1;
}

// `values` at the chosen channels of a residue vector (per channel).
Eigen::VectorXcd at_channels(const Eigen::VectorXcd& residues, const std::vector<Eigen::Index>& channels) {
  Eigen::VectorXcd v(static_cast<Eigen::Index>(channels.size()));
  for (std::size_t k = 0; k < channels.size(); ++k) v[static_cast<Eigen::Index>(k)] = residues[channels[k]];
  return v;
}

void write_svg(const std::string& dir, const std::string& file, const std::string& svg) {
  write_report_file((std::filesystem::path(dir) / file).string(), svg);
}

}  // namespace

void add_identified_mode_figures(report::Document& doc, const std::string& dir, const ModalReportInput& in) {
  if (!in.geometry || !in.model || in.result.modes.empty() || in.data.inputs.empty()) return;
  const ShapeGeometry& g = *in.geometry;
  const ModalData& data = in.data;
  const int reference = reference_input(data);
  std::vector<Eigen::Index> channels;
  SensorShape measured;
  for (std::size_t c = 0; c < data.channels.size(); ++c) {
    const ModalData::Channel& ch = data.channels[c];
    const int sensor = sensor_of(g, data.outputs[static_cast<std::size_t>(ch.output)]);
    if (ch.input != reference || sensor < 0) continue;
    channels.push_back(static_cast<Eigen::Index>(c));
    measured.sensor.push_back(sensor);
  }
  if (channels.empty()) return;
  const std::string& input = data.inputs[static_cast<std::size_t>(reference)];

  doc.heading(2, "Mode shapes against the model");
  doc.paragraph(report::Inline("Each identified mode's measured shape (small blue squares, dashed from rest): its "
                               "residues of the channels driven by ")
                << report::code(input)
                << ", each along its output's direction at the model's sensor point. With it (large red squares) the "
                   "paired model mode's residues at the same channels, turned and scaled by the one complex factor "
                   "that fits them best to the measured ones; then that model mode on the model's whole geometry. A "
                   "measured shape is known only at the sensors and only along their directions.");
  doc.paragraph(mode_shape_legend());
  std::set<int> drawn;
  for (std::size_t m = 0; m < in.result.modes.size(); ++m) {
    const IdentifiedMode& mode = in.result.modes[m];
    const std::string name = "identified mode " + std::to_string(m + 1);
    measured.value = at_channels(mode.residues, channels);
    std::vector<bool> points;
    const Eigen::Matrix3Xcd seen = sensor_translations(g, measured, points);
    ShapeLayer shown;
    shown.displacement = real_at_peak(seen, seen);
    shown.points = points;
    shown.lines = false;
    shown.arrows = true;
    shown.colour = kMeasuredColour;
    shown.legend = "measured: " + name + " (reference input " + input + ")";
    // The model's layer first, its marks larger, so that the measured ones stay visible on top of it.
    std::vector<ShapeLayer> layers;
    const int k = in.model->pairing.model_mode[m];
    if (k >= 0) {
      SensorShape model = measured;
      const Eigen::VectorXcd r = at_channels(in.model->modes.residues.row(k).transpose(), channels);
      const double norm = r.squaredNorm();
      model.value = norm > 0 ? (r * (r.dot(measured.value) / norm)).eval() : r;  // dot: r^H measured
      ShapeLayer& layer = layers.emplace_back();
      layer.displacement = real_at_peak(sensor_translations(g, model, points), seen);
      layer.points = points;
      layer.lines = false;
      layer.arrows = true;
      layer.colour = kModelColour;
      layer.marker = 1.7;
      layer.legend = "model mode " + std::to_string(k) + " at the same sensors (MAC " +
                     report_number(in.model->pairing.best_mac[m], 3) + ")";
    }
    layers.push_back(std::move(shown));
    const std::string file = "shape_identified_" + std::to_string(m + 1) + ".svg";
    const std::string title = mode_title(name, mode.f_hz, mode.zeta);
    write_svg(dir, file, mode_shape_svg(g, layers, title));
    doc.heading(3, report::Inline("Identified mode ") << m + 1);
    doc.figure(file, title);
    if (k < 0) continue;
    const std::string model_file = "shape_model_" + std::to_string(k) + ".svg";
    const std::size_t ki = static_cast<std::size_t>(k);
    const std::string model_title =
        mode_title("model mode " + std::to_string(k), in.model->modes.f_hz[ki], in.model->modes.zeta[ki]);
    if (drawn.insert(k).second)
      write_svg(dir, model_file, model_mode_svg(g, model_title, in.model->modes.shapes.col(k)));
    doc.figure(model_file, model_title);
  }
}

}  // namespace mbgen
