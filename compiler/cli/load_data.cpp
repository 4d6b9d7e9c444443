#include "cli/load_data.hpp"

#include <mbgen/data_error.hpp>
#include <mbgen/data_set.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>

#include <unistd.h>

namespace mbgen::cli {

std::vector<DataSet> load_data(const std::vector<std::string>& paths, const ModelInfo& model) {
  std::vector<DataSet> out;
  for (const std::string& path : paths) {
    DataFile file = read_data_file(path, model.inputs, model.outputs);
    out.push_back(std::visit([](auto&& d) { return DataSet(std::move(d)); }, std::move(file)));
  }
  return out;
}

Band parse_band(const std::string& option, const std::string& text) {
  const std::size_t colon = text.find(':');
  Band band;
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    std::size_t used = 0;
    band.lo = std::stod(text.substr(0, colon), &used);
    if (used != colon) throw std::invalid_argument("trailing text");
    band.hi = std::stod(text.substr(colon + 1), &used);
    if (used != text.size() - colon - 1) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw CLI::ValidationError(option, "expected LO:HI in Hz (e.g. 20:500), got `" + text + "`");
  }
  if (!(band.lo >= 0 && band.hi > band.lo && std::isfinite(band.hi)))
    throw CLI::ValidationError(option, "expected 0 <= LO < HI, got `" + text + "`");
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
