#include "cli/modal_start_option.hpp"

#include <algorithm>
#include <iostream>
#include <nlohmann/json.hpp>

namespace mbgen::cli {

ModalStart add_start_from_modes(const Model& model, const std::vector<DataSet>& data, FitOptions& options,
                                const std::string& command) {
  ModalStart start = start_from_modes(model, data, options);
  std::cerr << command << ": start from the data's modes: " << start.summary << "\n";
  if (start.values.empty()) return start;
  if (options.also_start_at.empty()) {
    options.also_start_at = start.values;
  } else {
    options.further_starts_at.insert(options.further_starts_at.begin(), options.also_start_at);
    options.also_start_at = start.values;
  }
  options.starts = std::max(options.starts, 2);
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
