// Fuzz target: `mbgen diagnose` of the mdof2 example on a short FRF file (issue 36: 2-15 lines crashed in the peak
// search, 24 lines ended in an internal error). The bytes go through the CSV reader; what it refuses ends there. A
// diagnosis must end in a verdict or in the errors the command reports as bad input (the model's, the data's, a
// fit's, the dynamics'); anything else is a bug. One start, one thread, two candidates fitted, one round: a run
// takes a fraction of a second, so inputs are limited to a few hundred lines.
#include <mbgen/data/data_error.hpp>
#include <mbgen/data/data_set.hpp>
#include <mbgen/dynamics/dynamics_error.hpp>
#include <mbgen/estimation/fit.hpp>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>

#include "diagnosis/engine/diagnose.hpp"
#include "frontend/diagnostics.hpp"
#include "frontend/parser.hpp"

namespace {

const std::string& mdof2_text() {
  static const std::string text = [] {
    std::ifstream in(MBGEN_MDOF2_MODEL, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }();
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 16384) return 0;
  static const mbgen::ir::ModelIr model = mbgen::frontend::parse_string(mdof2_text(), "mdof2.mdl");
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::optional<mbgen::DataSet> set;
  try {
    set = mbgen::read_data(in, "fuzz.csv", mbgen::ChannelNames{{"F1"}, {"d1", "d2"}});
  } catch (const mbgen::DataError&) {
    return 0;
  }
  if (!set->is_frf()) return 0;
  mbgen::diagnosis::DiagnoseOptions options;
  options.fit.starts = 1;
  options.fit.threads = 1;
  options.candidate_starts = 1;
  options.full_fits = 2;
  options.max_extensions = 1;
  try {
    mbgen::diagnosis::diagnose(model, mdof2_text(), {*set}, options);
  } catch (const mbgen::frontend::ModelError&) {
  } catch (const mbgen::DataError&) {
  } catch (const mbgen::FitError&) {
  } catch (const mbgen::DynamicsError&) {
  }
  return 0;
}
