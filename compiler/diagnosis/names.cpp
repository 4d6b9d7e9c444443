#include "diagnosis/names.hpp"

#include "ir/identifier.hpp"

namespace mbgen::diagnosis {

NameSet::NameSet(const ir::ModelIr& model) {
  for (const ir::Parameter& p : model.parameters) used_.insert(p.name);
  for (const ir::Ground& g : model.grounds) used_.insert(g.name);
  for (const ir::Body& b : model.bodies) used_.insert(b.name);
  for (const ir::Element& e : model.elements) used_.insert(e.name);
  for (const ir::Input& in : model.inputs) used_.insert(in.name);
  for (const ir::Output& out : model.outputs) used_.insert(out.name);
}

std::string NameSet::fresh(const std::string& base) {
  // Nor the language's reserved names and words: a parameter called `x` or `fixed` would be legal but confusing.
  const auto taken = [&](const std::string& n) {
    return used_.count(n) > 0 || ir::is_reserved_name(n) || ir::is_language_word(n);
  };
  std::string name = base;
  for (int k = 2; taken(name); ++k) name = base + "_" + std::to_string(k);
  used_.insert(name);
  return name;
}

}  // namespace mbgen::diagnosis
