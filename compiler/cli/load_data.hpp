// Reading the `--data` files of `fit` and `diagnose`: each checked against the model's inputs and outputs.
#pragma once

#include <mbgen/fit.hpp>

#include <string>
#include <vector>

namespace mbgen::cli {

std::vector<DataSet> load_data(const std::vector<std::string>& paths, const ModelInfo& model);

// A frequency band `LO:HI` in Hz, as `--band` and `--fit-band` take it (0 <= LO < HI); CLI::ValidationError
// naming `option` otherwise.
// A frequency band from the command line, "LO:HI" in Hz; either side may be left empty (0 and no upper limit).
// Bad text is a usage error (exit 2) naming `option`.
struct Band {
  double lo = 0, hi = 0;
};
Band parse_band(const std::string& option, const std::string& text);
// The FRF data sets' lines within the band. A time record has no lines to choose: DataError naming its file.
std::vector<DataSet> within_band(const std::vector<DataSet>& data, const Band& band);

// A progress line on standard error, overwritten in place on a terminal; nothing when not a terminal.
void progress_line(const std::string& text);
void progress_done();

}  // namespace mbgen::cli
