// Reading the `--data` files of `fit` and `diagnose`: each checked against the model's inputs and outputs.
#pragma once

#include <mbgen/estimation/fit.hpp>

#include <map>
#include <string>
#include <vector>

#include "ir/model_ir.hpp"

namespace mbgen::cli {

// The data sets at `paths`, their channels named as `model`'s inputs and outputs. Their `# set` values are checked
// as the command's `--set` values (`sets`) are (check_set_lines).
std::vector<DataSet> load_data(const std::vector<std::string>& paths, const ModelInfo& model, const ir::ModelIr& declared,
                               const std::map<std::string, std::string>& sets);

// Each `# set NAME=VALUE` of `data` checked by the code that checks `--set NAME=VALUE` (symbolic::ParameterTable),
// with the command's `--set` values beside it: NAME a declared parameter that is not derived, VALUE a decimal number
// within the limits on literals, within the range of a double and within the declared bounds, compared exactly
// (`# set third=0.3333333333333333` is below a bound of 1/3). A DataError at the `# set` line otherwise, naming the
// declaration. The fit checks the rest at the data set's values as it checks --set's: a positive definite mass
// matrix (estimation::check_data_set_values).
void check_set_lines(const ir::ModelIr& declared, const std::map<std::string, std::string>& sets,
                     const std::vector<DataSet>& data);

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
