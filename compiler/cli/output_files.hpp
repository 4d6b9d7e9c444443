// Outputs appear whole or not at all, and never at the cost of what the user had (docs/cli.md):
//
// - every file is written to a temporary beside its destination (`.NAME.mbgen-tmp-HOST-PID`) and renamed into
//   place only when all of a command's outputs are complete; an uncommitted set removes its temporaries, and
//   temporaries left by a killed run (same host, process gone) are removed by the next run writing there;
// - a report directory is written only where nothing of the user's can be lost: a new directory, an empty one, or
//   one that mbgen wrote before (it holds the marker file kReportMarker), which is then replaced whole;
// - no output may be an input, lie inside the report directory, or be named twice;
// - a destination that is a symbolic link, a character device or a named pipe (/dev/null, /dev/stdout) is written
//   through at commit, after the renames, instead of being replaced.
// "-" means standard output.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace mbgen::cli {

// A destination that cannot or must not be written (exit status 1): missing or read-only directory, a report
// directory holding files mbgen did not write, a failed write.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The file mbgen writes into every report directory; its presence allows the next run to replace the directory.
inline constexpr const char* kReportMarker = ".mbgen-report";

// A command's output destinations, checked before any long work.
struct OutputPlan {
  struct File {
    std::string option;  // "-o", "--json", ... (for messages)
    std::string path;    // "" = not requested, "-" = standard output
  };
  std::vector<File> files;
  std::string report_dir;           // "" = no report
  std::vector<std::string> inputs;  // the model and data files ("-" = standard input)

  // Throws CLI::ValidationError (usage, exit 2) for outputs that collide with each other, an input or the report
  // directory, and OutputError (exit 1) for a destination that cannot be written or a report directory that is
  // not mbgen's to replace.
  void check() const;
};

class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();  // removes temporaries of an uncommitted set

  // Stages `content` for `path`. Nothing is visible at `path` until commit().
  void add(const std::string& path, const std::string& content);
  // Stages a report directory that the caller fills: returns the temporary path to write into (it already holds
  // the marker file).
  std::string stage_directory(const std::string& dir);
  // Removes `path` at commit, once every output is in place (a stale output of an earlier run, such as a part file
  // a smaller --parts no longer writes).
  void remove(const std::string& path) { removed_.push_back(path); }
  // Renames every staged file into place (a report directory replaces the empty or mbgen-written directory there,
  // checked again now); throws OutputError on failure, having put back every destination it had already replaced.
  void commit();

 private:
  struct Staged {
    std::string temp, path;
    bool directory = false;
  };
  std::vector<Staged> staged_;
  struct Through {
    std::string path, content;
  };
  std::vector<Through> through_;  // destinations written through at commit (symbolic links, devices, pipes)
  std::vector<std::string> stdout_chunks_;
  std::vector<std::string> removed_;
  bool committed_ = false;
};

// Throws OutputError when something written to standard output did not reach it (a full disk, a closed stream,
// /dev/full): a command must not report success for output that was lost. Flushes first.
void require_standard_output_written();

}  // namespace mbgen::cli
