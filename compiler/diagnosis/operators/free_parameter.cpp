// free_parameter:P -- a parameter the model fixed by assumption (e.g. a damping taken as zero) is estimated.
#include "diagnosis/operators/operator_support.hpp"

namespace mbgen::diagnosis {

std::vector<Extension> free_parameter(const OperatorInput& in) {
  std::vector<Extension> out;
  for (std::size_t i = 0; i < in.model.parameters.size(); ++i) {
    const ir::Parameter& p = in.model.parameters[i];
    if (p.role != ir::Role::Fixed || p.derived) continue;  // a derived parameter cannot be estimated
    Draft d(in, "free_parameter", p.name);
    d.model().parameters[i].role = ir::Role::Estimate;
    d.free_parameter(p.name);
    d.patch().change_role(p.loc, "fixed", "estimate", "was fixed");
    const std::string unit = p.unit.empty() ? "" : " " + p.unit;
    out.push_back(d.finish("parameter " + p.name + ", assumed fixed at " + ir::to_string(p.value) + unit +
                           ", is estimated from the data instead"));
  }
  return out;
}

}  // namespace mbgen::diagnosis
