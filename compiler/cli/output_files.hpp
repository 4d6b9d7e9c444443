// Outputs appear whole or not at all: every file is written to a temporary beside its destination and renamed
// into place only when all of a command's outputs are complete. "-" means standard output.
#pragma once

#include <string>
#include <vector>

namespace mbgen::cli {

class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();  // removes temporaries of an uncommitted set

  // Fails early (before long work) when `path` could not be written: its directory is missing or read-only.
  static void require_writable(const std::string& path);

  // Stages `content` for `path`. Nothing is visible at `path` until commit().
  void add(const std::string& path, const std::string& content);
  // Stages a directory that the caller fills (e.g. a report writer): returns the temporary path to write into.
  std::string stage_directory(const std::string& dir);
  // Renames every staged file into place; throws std::runtime_error on failure.
  void commit();

 private:
  struct Staged {
    std::string temp, path;
    bool directory = false;
  };
  std::vector<Staged> staged_;
  std::vector<std::string> stdout_chunks_;
  bool committed_ = false;
};

}  // namespace mbgen::cli
