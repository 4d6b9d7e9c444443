#include <algorithm>
#include <set>
#include <stdexcept>

#include "diagnosis/extension.hpp"
#include "frontend/model_writer.hpp"
#include "frontend/parser.hpp"
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

namespace {

// The candidates for one context, in the order of enumerate_extensions.
std::vector<Extension> candidates(const ir::ModelIr& located, const std::string& text, const ExtensionContext& ctx) {
  const OperatorInput in{located, text, ctx, ModelValues(located, ctx.values)};
  std::vector<Extension> out;
  for (auto op : {measurement_chain, compliant_ground, gyroscopic, free_parameter, untie_parameter, moment_stiffness,
                  added_mass, resonator, sensor_dynamics, connection}) {
    std::vector<Extension> found;
    try {
      found = op(in);
    } catch (const UnusableStart&) {
      continue;  // its start values have no value at the current estimate: no candidate of this operator
    }
    for (Extension& e : found) out.push_back(std::move(e));
  }
  return out;
}

// The start values of e's new parameters.
std::map<std::string, double> new_parameter_starts(const Extension& e) {
  const ModelValues values(e.model, {});
  std::map<std::string, double> out;
  for (const NewParameter& p : e.new_parameters) out[p.name] = values.of_parameter(p.name);
  return out;
}

// Extension::alternative_starts: the operators asked again with each of the next peaks first; a candidate whose
// new parameters then start elsewhere gets those starts (once each).
void add_alternative_starts(std::vector<Extension>& out, const ir::ModelIr& located, const std::string& text,
                            const ExtensionContext& ctx) {
  std::vector<std::map<std::string, double>> own;
  for (const Extension& e : out) own.push_back(new_parameter_starts(e));
  for (std::size_t p = 1; p < ctx.peak_hz.size() && p <= kAlternativePeaks; ++p) {
    ExtensionContext rotated = ctx;
    rotated.peak_hz.erase(rotated.peak_hz.begin() + static_cast<std::ptrdiff_t>(p));
    rotated.peak_hz.insert(rotated.peak_hz.begin(), ctx.peak_hz[p]);
    const std::vector<Extension> again = candidates(located, text, rotated);
    for (std::size_t i = 0; i < out.size(); ++i) {
      Extension& e = out[i];
      const auto same = std::find_if(again.begin(), again.end(), [&](const Extension& a) {
        return a.id == e.id && a.variant == e.variant && a.new_parameters.size() == e.new_parameters.size();
      });
      if (same == again.end()) continue;
      // The operators write start values as literals, so a start that does not depend on the peak is equal.
      std::map<std::string, double> start = new_parameter_starts(*same);
      const bool same_names = std::equal(start.begin(), start.end(), own[i].begin(), own[i].end(),
                                         [](const auto& a, const auto& b) { return a.first == b.first; });
      if (same_names && start != own[i] &&
          std::find(e.alternative_starts.begin(), e.alternative_starts.end(), start) == e.alternative_starts.end())
        e.alternative_starts.push_back(std::move(start));
    }
  }
}

}  // namespace

std::vector<Extension> enumerate_extensions(const ir::ModelIr& nominal, const std::string& nominal_text,
                                            const ExtensionContext& ctx) {
  // The operators edit the text at the locations the parser records, so they work on the model parsed from
  // that very text (a model built in code is written out first).
  const std::string text = nominal_text.empty() ? frontend::write_model(nominal) : nominal_text;
  const std::string file = nominal.file.empty() ? "model.mdl" : nominal.file;
  const ir::ModelIr located = frontend::parse_string(text, file);
  if (frontend::write_model(located) != frontend::write_model(nominal))
    throw std::invalid_argument("enumerate_extensions: the model is not the one its text `" + file + "` describes");

  std::vector<Extension> out = candidates(located, text, ctx);
  add_alternative_starts(out, located, text, ctx);
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
