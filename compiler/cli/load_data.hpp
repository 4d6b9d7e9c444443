// Reading the `--data` files of `fit` and `diagnose`: each checked against the model's inputs and outputs.
#pragma once

#include <mbgen/fit.hpp>

#include <string>
#include <vector>

namespace mbgen::cli {

std::vector<DataSet> load_data(const std::vector<std::string>& paths, const ModelInfo& model);

// A progress line on standard error, overwritten in place on a terminal; nothing when not a terminal.
void progress_line(const std::string& text);
void progress_done();

}  // namespace mbgen::cli
