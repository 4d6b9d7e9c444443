#include "symbolic/symbolic_model.hpp"

namespace mbgen::symbolic {

std::string Coordinate::name() const { return body + "." + (state.empty() ? std::string(ir::to_string(dof)) : state); }

GiNaC::exmap SymbolicModel::values() const {
  GiNaC::exmap m;
  for (const FreeParameter& p : parameters) m[p.sym] = p.value;
  return m;
}

int SymbolicModel::parameter_index(const std::string& name) const {
  for (size_t i = 0; i < parameters.size(); ++i)
    if (parameters[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace mbgen::symbolic
