#include "cli/modal_synthesis.hpp"

#include <mbgen/data/csv.hpp>
#include <mbgen/data/data_error.hpp>

#include <optional>
#include <sstream>

#include "cli/frf_uff58.hpp"

namespace mbgen::cli {

DataTexts synthesis_texts(const ModalData& data, const ModalIdentification& result, DataFormat format,
                          const std::vector<std::string>& data_paths, const ir::ModelIr* model,
                          const std::map<std::string, std::string>& sets) {
  FrfData frf;
  frf.file = data_paths.front();
  frf.f_hz = data.f_hz;
  for (std::size_t c = 0; c < data.channels.size(); ++c) {
    const ModalData::Channel& ch = data.channels[c];
    frf.channels.push_back({data.outputs[static_cast<std::size_t>(ch.output)],
                            data.inputs[static_cast<std::size_t>(ch.input)],
                            result.fit.synthesized.col(static_cast<Eigen::Index>(c)), std::nullopt});
  }
  frf.uff_ordinate_type = uff_specific_data_type(data.quantity);
  if (format == DataFormat::Csv) {
    std::ostringstream out;
    write_frf_csv(out, frf);
    return {out.str(), ""};
  }
  UffPointRules rules;
  rules.mappings = own_mappings(data_paths);
  std::optional<SensorGeometry> geometry;
  if (model) {
    std::map<std::string, double> values;
    for (const auto& [name, text] : sets) values[name] = std::stod(text);  // checked by parse_set_options
    try {
      rules.model_outputs = &geometry.emplace(sensor_geometry(*model, values));
    } catch (const DataError&) {
      // An output off the global axes has no UFF direction: the channels keep their own or the default points.
    }
    for (const ir::Input& in : model->inputs) rules.model_inputs.push_back(in.name);
  }
  const UffText uff = frf_uff58_text(frf, rules, "mbgen modal synthesis");
  return {uff.data, uff.mapping};
}

}  // namespace mbgen::cli
