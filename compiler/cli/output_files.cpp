#include "cli/output_files.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include <unistd.h>

namespace mbgen::cli {

namespace fs = std::filesystem;

namespace {

std::string temp_name_for(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / ("." + p.filename().string() + ".mbgen-tmp-" + std::to_string(::getpid()))).string();
}

void write_file(const std::string& path, const std::string& content, const std::string& shown_as) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(shown_as + ": error: cannot write: " + std::strerror(errno));
  out << content;
  out.close();
  if (!out) throw std::runtime_error(shown_as + ": error: writing failed: " + std::strerror(errno));
}

}  // namespace

void OutputFiles::require_writable(const std::string& path) {
  if (path.empty() || path == "-") return;
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error(path + ": error: cannot write: directory `" + dir.string() + "` does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error(path + ": error: cannot write: directory `" + dir.string() + "` is not writable");
}

OutputFiles::~OutputFiles() {
  if (committed_) return;
  std::error_code ec;
  for (const Staged& s : staged_) fs::remove_all(s.temp, ec);
}

void OutputFiles::add(const std::string& path, const std::string& content) {
  if (path == "-") {
    stdout_chunks_.push_back(content);
    return;
  }
  const std::string temp = temp_name_for(path);
  staged_.push_back({temp, path, false});
  write_file(temp, content, path);
}

std::string OutputFiles::stage_directory(const std::string& dir) {
  const std::string temp = temp_name_for(fs::path(dir).lexically_normal().string());
  std::error_code ec;
  fs::remove_all(temp, ec);
  staged_.push_back({temp, dir, true});
  if (!fs::create_directories(temp, ec) && ec) throw std::runtime_error(dir + ": error: cannot create: " + ec.message());
  return temp;
}

void OutputFiles::commit() {
  for (const Staged& s : staged_) {
    std::error_code ec;
    if (s.directory) fs::remove_all(s.path, ec);  // a report directory is replaced as a whole
    fs::rename(s.temp, s.path, ec);
    if (ec) throw std::runtime_error(s.path + ": error: cannot move the output into place: " + ec.message());
  }
  for (const std::string& chunk : stdout_chunks_) std::cout << chunk;
  std::cout.flush();
  committed_ = true;
}

}  // namespace mbgen::cli
