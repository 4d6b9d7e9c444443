// model_text -- the diagnosis's edits of a model's .mdl text, all through TextPatch (diagnosis/text_patch.hpp), so
// the written extended model keeps the user's layout and comments and says what changed.
#pragma once

#include <map>
#include <set>
#include <string>

#include "diagnosis/engine/diagnose.hpp"

namespace mbgen::diagnosis {

// `text` (from `file`) with the start values of the parameters in `names` replaced by their `values` (six
// significant digits), so that the written model is the fitted one. Derived parameters keep their expressions.
std::string with_estimates(const std::string& text, const std::string& file,
                           const std::map<std::string, double>& values, const std::set<std::string>& names);

// `text` with parameter `name`'s declaration changed from `estimate` to `known`, saying why in its comment.
std::string with_role_known(const std::string& text, const std::string& file, const std::string& name);

// The parameters a taken model's fit held (ModelState::held) become `known` in its model and text, so that later
// fits keep them and the written model says so.
void declare_held_known(ModelState& s);

// The names of the parameters the selected extensions added.
std::set<std::string> added_parameters(const DiagnosisResult& r);

}  // namespace mbgen::diagnosis
