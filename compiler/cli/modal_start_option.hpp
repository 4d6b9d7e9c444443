// --start-from-modes (fit, diagnose, monitor; docs/cli.md): one more start of the output-error search, placed on the
// data's own modes (mbgen/methods/modal_start.hpp).
#pragma once

#include <mbgen/estimation/fit.hpp>
#include <mbgen/methods/modal_start.hpp>

#include <string>
#include <vector>

namespace mbgen::cli {

// Places the start and adds it to `options` as the search's first chosen start (before any other chosen start),
// with at least two starts so the priors keep theirs; says on standard error what it did (`command`: "fit").
ModalStart add_start_from_modes(const Model& model, const std::vector<DataSet>& data, FitOptions& options,
                                const std::string& command);

// The start's account for a result's method_details["start_from_modes"]: summary, modes, values.
std::string start_from_modes_details(const ModalStart& start);

}  // namespace mbgen::cli
