#include "diagnosis/engine/model_text.hpp"

#include <algorithm>
#include <cstdio>

#include "diagnosis/text_patch.hpp"
#include "frontend/parser.hpp"

namespace mbgen::diagnosis {

std::string with_estimates(const std::string& text, const std::string& file,
                           const std::map<std::string, double>& values, const std::set<std::string>& names) {
  const ir::ModelIr parsed = frontend::parse_string(text, file);
  TextPatch patch(text, file);
  for (const ir::Parameter& p : parsed.parameters) {
    const auto it = values.find(p.name);
    if (!names.count(p.name) || it == values.end() || p.derived) continue;
    char number[64];
    std::snprintf(number, sizeof number, "%.6g", it->second);
    patch.replace_number(p.loc, number);
  }
  return patch.text();
}

std::string with_role_known(const std::string& text, const std::string& file, const std::string& name) {
  const ir::ModelIr parsed = frontend::parse_string(text, file);
  TextPatch patch(text, file);
  for (const ir::Parameter& p : parsed.parameters)
    if (p.name == name && p.role == ir::Role::Estimate)
      patch.change_role(p.loc, "estimate", "known", "held at this value: the data do not determine it");
  return patch.text();
}

void declare_held_known(ModelState& s) {
  for (const std::string& name : s.held) {
    for (ir::Parameter& p : s.model.parameters)
      if (p.name == name) p.role = ir::Role::Known;
    s.text = with_role_known(s.text, s.model.file, name);
  }
  s.held.clear();
}

std::set<std::string> added_parameters(const DiagnosisResult& r) {
  std::set<std::string> names;
  for (const CandidateOutcome& c : r.candidates)
    if (std::find(r.selected.begin(), r.selected.end(), c.id) != r.selected.end())
      for (const NewParameter& p : c.new_parameters) names.insert(p.name);
  return names;
}

}  // namespace mbgen::diagnosis
