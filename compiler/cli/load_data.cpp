#include "cli/load_data.hpp"

#include <mbgen/data_set.hpp>

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
