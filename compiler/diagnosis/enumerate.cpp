#include <set>
#include <stdexcept>

#include "diagnosis/extension.hpp"
#include "frontend/model_writer.hpp"
#include "frontend/parser.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

std::vector<Extension> enumerate_extensions(const ir::ModelIr& nominal, const std::string& nominal_text,
                                            const ExtensionContext& ctx) {
  // The operators edit the text at the locations the parser records, so they work on the model parsed from
  // that very text (a model built in code is written out first).
  const std::string text = nominal_text.empty() ? frontend::write_model(nominal) : nominal_text;
  const std::string file = nominal.file.empty() ? "model.mdl" : nominal.file;
  const ir::ModelIr located = frontend::parse_string(text, file);
  if (frontend::write_model(located) != frontend::write_model(nominal))
    throw std::invalid_argument("enumerate_extensions: the model is not the one its text `" + file + "` describes");

  const OperatorInput in{located, text, ctx, ModelValues(located, ctx.values)};
  std::vector<Extension> out;
  for (auto op : {compliant_ground, gyroscopic, free_parameter, untie_parameter, moment_stiffness, added_mass,
                  resonator, sensor_dynamics, connection}) {
    std::vector<Extension> found = op(in);
    for (Extension& e : found) out.push_back(std::move(e));
  }
  // An id appears once, or as a run of consecutive variants with distinct names.
  std::set<std::string> ids, variants;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Extension& e = out[i];
    const bool continues = i > 0 && out[i - 1].id == e.id && !e.variant.empty() && !out[i - 1].variant.empty();
    if (!continues) variants.clear();
    if ((!continues && !ids.insert(e.id).second) || (!e.variant.empty() && !variants.insert(e.variant).second))
      throw std::logic_error("enumerate_extensions: candidate id `" + e.id + "` twice");
  }
  return out;
}

}  // namespace mbgen::diagnosis
