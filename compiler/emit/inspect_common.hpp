// What the three inspection formats share: names, numeric values and modes at the current values.
#pragma once

#include <string>
#include <vector>

#include "mbgen/dynamics/model_modes.hpp"
#include "symbolic/symbolic_model.hpp"

namespace mbgen::emit::detail {

struct InspectNames {
  std::vector<std::string> coordinates, inputs, outputs;
};

InspectNames inspect_names(const symbolic::SymbolicModel& sm);

double value_as_double(const GiNaC::ex& e);  // evalf of a constant expression
const char* role_name(const symbolic::FreeParameter& p);  // "known", "estimate", "fixed"
std::string unit_of(const symbolic::FreeParameter& p);

// Modes at the current parameter values (M, C_total, K evaluated to double), sorted by frequency.
std::vector<Mode> modes_at_current_values(const symbolic::SymbolicModel& sm);

// True if G has a non-zero entry.
bool has_spin(const symbolic::SymbolicModel& sm);

// "%.6g"-style text of a double, for human-readable formats.
std::string short_number(double x);

}  // namespace mbgen::emit::detail
