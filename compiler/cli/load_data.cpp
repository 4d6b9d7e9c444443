#include "cli/load_data.hpp"

#include <mbgen/data/data_error.hpp>
#include <mbgen/data/data_set.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <stdexcept>

#include <unistd.h>

#include "frontend/diagnostics.hpp"
#include "symbolic/to_ginac.hpp"

namespace mbgen::cli {

std::vector<DataSet> load_data(const std::vector<std::string>& paths, const ModelInfo& model, const ir::ModelIr& declared,
                               const std::map<std::string, std::string>& sets) {
  std::vector<DataSet> out;
  for (const std::string& path : paths) out.push_back(read_data_file(path, model.inputs, model.outputs));
  check_set_lines(declared, sets, out);
  return out;
}

void check_set_lines(const ir::ModelIr& declared, const std::map<std::string, std::string>& sets,
                     const std::vector<DataSet>& data) {
  for (const DataSet& d : data)
    for (const auto& [name, value] : d.set()) {
      std::map<std::string, std::string> overrides = sets;
      overrides[name] = value.text;  // a data set's value replaces --set's for that data set
      try {
        const symbolic::ParameterTable checked(declared, overrides, "# set");
      } catch (const frontend::ModelError& e) {
        const std::string at =
            e.loc().line > 0 ? fmt::format(" ({}:{}:{})", e.file(), e.loc().line, e.loc().column) : "";
        throw DataError(d.file(), value.line, 0, e.message() + at);
      }
    }
}

Band parse_band(const std::string& option, const std::string& text) {
  const std::size_t colon = text.find(':');
  const auto fail = [&] {
    return CLI::ValidationError(option, "expected LO:HI in Hz with 0 <= LO < HI, either side may be left empty "
                                        "(e.g. 20:500, :500), got `" + text + "`");
  };
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos) throw fail();
  Band band;
  band.hi = std::numeric_limits<double>::infinity();
  const auto number = [&](const std::string& s, double& out) {
    if (s.empty()) return;  // an open side
    std::size_t used = 0;
    try {
      out = std::stod(s, &used);
    } catch (const std::invalid_argument&) {  // what std::stod throws for text that is no number
      throw fail();
    } catch (const std::out_of_range&) {  // and for one beyond a double
      throw fail();
    }
    if (used != s.size() || !std::isfinite(out)) throw fail();
  };
  number(text.substr(0, colon), band.lo);
  number(text.substr(colon + 1), band.hi);
  if (!(band.lo >= 0 && band.lo < band.hi)) throw fail();
  return band;
}

std::vector<DataSet> within_band(const std::vector<DataSet>& data, const Band& band) {
  std::vector<DataSet> out;
  for (const DataSet& d : data) {
    const FrfData* frf = std::get_if<FrfData>(&d.content);
    if (!frf) throw DataError(d.file(), 0, 0, "a frequency band selects FRF lines, and this is a time record");
    try {
      out.emplace_back(mbgen::within_band(*frf, band.lo, band.hi));
    } catch (const std::invalid_argument&) {
      throw DataError(d.file(), 0, 0, "no frequency line within the band: nothing to fit");
    }
  }
  return out;
}

namespace {
bool& line_open() {
  static bool open = false;
  return open;
}
}  // namespace

void progress_line(const std::string& text) {
  if (!::isatty(STDERR_FILENO)) return;
  std::fprintf(stderr, "\r\033[K%s", text.c_str());
  std::fflush(stderr);
  line_open() = true;
}

void progress_done() {
  if (!line_open()) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  line_open() = false;
}

}  // namespace mbgen::cli
