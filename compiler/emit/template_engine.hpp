// A deliberately tiny template engine for the emitters: the text of emitted files lives in templates/.
//
// Syntax:
//   {{name}}               the value of `name` (a string; inserted verbatim, no escaping)
//   {{#name}}...{{/name}}  the enclosed text once per dictionary of the list `name`; inside, names are looked up
//                          in that dictionary first, then in the enclosing ones
//   {{! comment }}         nothing (template comments)
// A placeholder naming nothing known, a string used as a list (or the reverse) and unbalanced sections are
// errors (TemplateError), so a typo in a template never yields silently wrong code.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace mbgen::emit {

class TemplateError : public std::runtime_error {
 public:
  explicit TemplateError(const std::string& what) : std::runtime_error(what) {}
};

struct TemplateValue;
using TemplateDict = std::map<std::string, TemplateValue>;
using TemplateList = std::vector<TemplateDict>;

struct TemplateValue {
  std::variant<std::string, TemplateList> value;
  TemplateValue() = default;
  TemplateValue(std::string s) : value(std::move(s)) {}  // NOLINT: implicit on purpose, reads naturally
  TemplateValue(const char* s) : value(std::string(s)) {}  // NOLINT
  TemplateValue(TemplateList l) : value(std::move(l)) {}  // NOLINT
};

// Renders `text` (the template called `template_name` in error messages) with `values`.
std::string render_template(const std::string& text, const TemplateDict& values,
                            const std::string& template_name = "<template>");

// The text of an embedded template, e.g. "cpp/model.hpp.tmpl" (generated at build time from templates/).
// Throws TemplateError for an unknown name.
const std::string& embedded_template(const std::string& name);

// Shorthand: render_template(embedded_template(name), values, name).
std::string render_embedded(const std::string& name, const TemplateDict& values);

}  // namespace mbgen::emit
