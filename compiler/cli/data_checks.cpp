#include "cli/data_checks.hpp"

#include "diagnosis/engine/driving_points.hpp"

namespace mbgen::cli {

std::vector<std::string> passivity_warnings(const ir::ModelIr& model, const std::vector<DataSet>& data) {
  std::vector<std::string> out;
  for (const diagnosis::ReversedDrivingPoint& p : diagnosis::reversed_driving_points(model, data))
    out.push_back(diagnosis::describe(p));
  return out;
}

}  // namespace mbgen::cli
