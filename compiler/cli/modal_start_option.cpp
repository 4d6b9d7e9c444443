#include "cli/modal_start_option.hpp"

#include <iostream>
#include <nlohmann/json.hpp>

namespace mbgen::cli {

ModalStart add_start_from_modes(const Model& model, const std::vector<DataSet>& data, FitOptions& options,
                                const std::string& command) {
  ModalStart start = start_from_modes(model, data, options);
  std::cerr << command << ": start from the data's modes: " << start.summary << "\n";
  start_first_at(start.values, options);
  return start;
}

std::string start_from_modes_details(const ModalStart& start) {
  nlohmann::json j;
  j["summary"] = start.summary;
  j["modes_hz"] = start.f_hz;
  j["values"] = start.values;
  j["misfit_at_prior"] = start.cost_at_prior;
  j["misfit"] = start.cost;
  return j.dump();
}

}  // namespace mbgen::cli
