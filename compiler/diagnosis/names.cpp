#include "diagnosis/names.hpp"

namespace mbgen::diagnosis {

NameSet::NameSet(const ir::Model& model) {
  // Keywords of the language and the constants: a parameter called `x` or `fixed` would be legal but confusing.
  used_ = {"pi", "inf", "sqrt", "sin", "cos", "x", "y", "z", "rx", "ry", "rz", "known", "estimate", "fixed", "in"};
  for (const ir::Parameter& p : model.parameters) used_.insert(p.name);
  for (const ir::Ground& g : model.grounds) used_.insert(g.name);
  for (const ir::Body& b : model.bodies) used_.insert(b.name);
  for (const ir::Element& e : model.elements) used_.insert(e.name);
  for (const ir::Input& in : model.inputs) used_.insert(in.name);
  for (const ir::Output& out : model.outputs) used_.insert(out.name);
}

std::string NameSet::fresh(const std::string& base) {
  std::string name = base;
  for (int k = 2; used_.count(name); ++k) name = base + "_" + std::to_string(k);
  used_.insert(name);
  return name;
}

}  // namespace mbgen::diagnosis
