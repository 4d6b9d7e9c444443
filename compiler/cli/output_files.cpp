#include "cli/output_files.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

#include <sys/stat.h>
#include <unistd.h>

#include "frontend/message.hpp"

namespace mbgen::cli {

namespace fs = std::filesystem;

namespace {

// `path` without `.` and `..` steps or a trailing separator ("old/" names the directory old).
fs::path clean(const std::string& path) {
  fs::path p = fs::path(path).lexically_normal();
  if (p.filename().empty() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  return p;
}

fs::path parent_of(const fs::path& p) {
  const fs::path parent = p.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

// Absolute, with symbolic links resolved as far as the path exists.
fs::path resolved(const fs::path& p) {
  std::error_code ec;
  const fs::path r = fs::weakly_canonical(fs::absolute(p, ec), ec);
  return ec ? fs::absolute(p).lexically_normal() : r;
}

bool same_path(const fs::path& a, const fs::path& b) { return resolved(a) == resolved(b); }

// Whether `path` (following symbolic links) is the file standard input reads: the same device and inode. Standard
// input is an input like any other (`mbgen fit m.mdl --data - --json data.csv < data.csv` would replace the data).
bool is_standard_input(const fs::path& path) {
  struct stat in {}, out {};
  if (::fstat(STDIN_FILENO, &in) != 0 || !S_ISREG(in.st_mode)) return false;
  return ::stat(path.c_str(), &out) == 0 && in.st_dev == out.st_dev && in.st_ino == out.st_ino;
}

// The regular file standard input reads, as a path (Linux: /proc/self/fd/0), or "" when it is none (a pipe, a
// terminal): for the check that a report directory does not hold it.
fs::path standard_input_file() {
  struct stat in {};
  if (::fstat(STDIN_FILENO, &in) != 0 || !S_ISREG(in.st_mode)) return {};
  std::error_code ec;
  const fs::path target = fs::read_symlink("/proc/self/fd/0", ec);
  return ec || !target.is_absolute() ? fs::path() : target;
}

// True if `p` is `dir` or lies below it.
bool within(const fs::path& p, const fs::path& dir) {
  const fs::path rp = resolved(p), rd = resolved(dir);
  auto pi = rp.begin();
  for (auto di = rd.begin(); di != rd.end(); ++di, ++pi) {
    if (di->empty()) continue;  // a trailing separator
    if (pi == rp.end() || *pi != *di) return false;
  }
  return true;
}

// The host name as it may appear in a file name.
std::string host_tag() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "host";
  std::string out;
  for (const char* c = name; *c; ++c) out += std::isalnum(static_cast<unsigned char>(*c)) || *c == '-' ? *c : '_';
  return out.empty() ? "host" : out;
}

// `.NAME.mbgen-KIND-HOST-`: the prefix of the temporaries (KIND "tmp") and set-aside directories (KIND "old")
// of destination NAME; the process id follows.
std::string temp_prefix(const fs::path& destination, const char* kind) {
  return "." + destination.filename().string() + ".mbgen-" + kind + "-" + host_tag() + "-";
}

fs::path temp_for(const fs::path& destination, const char* kind) {
  return parent_of(destination) / (temp_prefix(destination, kind) + std::to_string(::getpid()));
}

// Removes what a killed run of mbgen on this host left for `destination`: temporaries whose process is gone.
void remove_stale_temporaries(const fs::path& destination) {
  std::error_code ec;
  for (const char* kind : {"tmp", "old"}) {
    const std::string prefix = temp_prefix(destination, kind);
    for (fs::directory_iterator it(parent_of(destination), ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (name.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string pid_text = name.substr(prefix.size());
      if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos || pid_text.size() > 9)
        continue;
      const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
      if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
      std::error_code remove_ec;
      fs::remove_all(it->path(), remove_ec);
    }
  }
}

[[noreturn]] void fail(const fs::path& path, const std::string& message) {
  throw OutputError(frontend::error_text(path.string(), ir::SourceLoc{}, message));
}

void require_writable_directory(const fs::path& destination) {
  const fs::path dir = parent_of(destination);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail(destination, "cannot write: directory `" + dir.string() + "` does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    fail(destination, "cannot write: directory `" + dir.string() + "` is not writable");
}

// A destination that is a symbolic link, a character device or a named pipe (`/dev/null`, `/dev/stdout`, a link of
// the user's) is written through, not replaced by a renamed temporary: the rename put a regular file in its place
// (as root, /dev/null itself) and dropped the user's link.
bool written_through(const fs::path& destination) {
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(destination, ec))) return true;
  const fs::file_status st = fs::status(destination, ec);
  return fs::is_character_file(st) || fs::is_fifo(st);
}

// What a written-through destination needs: write permission on what exists (its directory need not be writable:
// /dev is not, for a user), or on the directory where a dangling link's target would be made.
void require_writable_through(const fs::path& destination) {
  std::error_code ec;
  const fs::file_status st = fs::status(destination, ec);
  if (!fs::exists(st)) {
    require_writable_directory(resolved(destination));
  } else if (!fs::is_regular_file(st) && !fs::is_character_file(st) && !fs::is_fifo(st)) {
    fail(destination, "cannot write: it is neither a file, a character device nor a named pipe");
  } else if (::access(destination.c_str(), W_OK) != 0) {
    fail(destination, std::string("cannot write: ") + std::strerror(errno));
  }
}

// Every entry below `dir`, relative to it, directories with a trailing '/', sorted.
std::vector<std::string> entries_below(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  fs::recursive_directory_iterator it(dir, fs::directory_options::none, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    std::string rel = it->path().lexically_relative(dir).generic_string();
    if (it->is_directory(ec) && !it->is_symlink(ec)) rel += '/';
    out.push_back(rel);
  }
  if (ec) fail(dir, "cannot read the directory: " + ec.message());
  std::sort(out.begin(), out.end());
  return out;
}

const char* const kMarkerHeading =
    "This directory was written by mbgen. The next mbgen run that writes a report here replaces it whole, as long\n"
    "as it holds nothing but these entries:\n";

std::vector<std::string> marker_entries(const fs::path& dir) {
  std::ifstream in(dir / kReportMarker, std::ios::binary);
  std::vector<std::string> out;
  std::string line;
  for (int skip = 2; skip > 0 && std::getline(in, line); --skip) {
  }
  while (std::getline(in, line))
    if (!line.empty()) out.push_back(line);
  return out;
}

enum class ReportTarget { New, Empty, Mbgen };

// What is at `dir` now, or OutputError when a report must not be written there.
ReportTarget report_target(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(dir, ec);
  if (within(fs::current_path(ec), dir))
    fail(dir, "cannot write a report here: it is the working directory or contains it; name a new directory");
  if (!fs::exists(st)) {
    require_writable_directory(dir);
    return ReportTarget::New;
  }
  if (fs::is_symlink(st)) fail(dir, "cannot write a report here: it is a symbolic link; name the directory itself");
  if (!fs::is_directory(st))
    fail(dir, "cannot write a report here: it exists and is not a directory; name a new directory");
  require_writable_directory(dir);  // it is renamed and replaced in its parent
  const std::vector<std::string> present = entries_below(dir);
  if (present.empty()) return ReportTarget::Empty;
  if (!fs::is_regular_file(fs::symlink_status(dir / kReportMarker, ec)))
    fail(dir, "cannot write a report here: the directory holds files that mbgen did not write (it has no " +
                  std::string(kReportMarker) + " marker), and they would be lost; name a new or empty directory");
  std::vector<std::string> written = marker_entries(dir);
  written.push_back(kReportMarker);
  std::sort(written.begin(), written.end());
  for (const std::string& entry : present)
    if (!std::binary_search(written.begin(), written.end(), entry))
      fail(dir, "cannot write a report here: `" + entry +
                    "` was not written by mbgen and would be lost when the report is replaced; move it, or name a "
                    "new directory");
  return ReportTarget::Mbgen;
}

void write_file(const fs::path& path, const std::string& content, const fs::path& shown_as) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) fail(shown_as, std::string("cannot write: ") + std::strerror(errno));
  out << content;
  out.close();
  if (!out) fail(shown_as, std::string("writing failed: ") + std::strerror(errno));
}

void write_marker(const fs::path& staged) {
  std::ostringstream text;
  text << kMarkerHeading << "\n";
  for (const std::string& entry : entries_below(staged)) text << entry << "\n";
  write_file(staged / kReportMarker, text.str(), staged);
}

}  // namespace

void OutputPlan::check() const {
  if (std::count(inputs.begin(), inputs.end(), "-") > 1)
    throw CLI::ValidationError("input", "standard input (-) can be read only once: give the other inputs as files");
  std::vector<std::pair<std::string, fs::path>> written;  // option, path
  for (const File& f : files)
    if (!f.path.empty() && f.path != "-") written.emplace_back(f.option, clean(f.path));
  for (std::size_t i = 0; i < written.size(); ++i) {
    const auto& [option, path] = written[i];
    for (std::size_t k = 0; k < i; ++k)
      if (same_path(path, written[k].second))
        throw CLI::ValidationError(option, path.string() + " is also the output of " + written[k].first +
                                               "; give each output its own name");
    for (const std::string& input : inputs) {
      if (input != "-" && same_path(path, clean(input)))
        throw CLI::ValidationError(option, path.string() + " is an input of this command; writing it would destroy it");
      if (input == "-" && is_standard_input(path))
        throw CLI::ValidationError(option, path.string() + " is the file standard input (-) reads, an input of this "
                                                           "command; writing it would destroy it");
    }
    if (!report_dir.empty() && within(path, clean(report_dir)))
      throw CLI::ValidationError(option, path.string() + " lies inside the report directory " + report_dir +
                                             ", which is written whole; write it elsewhere");
    std::error_code ec;
    if (fs::is_directory(path, ec)) fail(path, "cannot write: it is a directory");
    if (written_through(path)) {
      require_writable_through(path);
      continue;
    }
    if (fs::exists(fs::status(path, ec)) && !fs::is_regular_file(fs::status(path, ec)))
      fail(path, "cannot write: it is neither a file, a character device nor a named pipe");
    require_writable_directory(path);
  }
  if (report_dir.empty()) return;
  // Elsewhere `-` means standard output, which cannot hold a directory; it made a directory named `-`.
  if (report_dir == "-")
    throw CLI::ValidationError("--report", "- (standard output) cannot hold a report directory; name a directory");
  const fs::path dir = clean(report_dir);
  report_target(dir);
  for (const std::string& input : inputs) {
    const fs::path file = input == "-" ? standard_input_file() : clean(input);
    if (!file.empty() && within(file, dir))
      fail(dir, "cannot write a report here: it holds the input " + (input == "-" ? file.string() + " (standard input)" : input) +
                    ", which replacing it would delete");
  }
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
  const fs::path destination = clean(path);
  if (written_through(destination)) {
    through_.push_back({destination.string(), content});
    return;
  }
  remove_stale_temporaries(destination);
  const fs::path temp = temp_for(destination, "tmp");
  staged_.push_back({temp.string(), destination.string(), false});
  write_file(temp, content, destination);
}

std::string OutputFiles::stage_directory(const std::string& dir) {
  const fs::path destination = clean(dir);
  remove_stale_temporaries(destination);
  const fs::path temp = temp_for(destination, "tmp");
  std::error_code ec;
  fs::remove_all(temp, ec);
  staged_.push_back({temp.string(), destination.string(), true});
  if (!fs::create_directory(temp, ec)) fail(destination, "cannot create: " + ec.message());
  return temp.string();
}

void OutputFiles::commit() {
  // Everything that can be checked first is: a report directory (again: files may have appeared meanwhile), and
  // that no file's destination has become a directory.
  std::vector<ReportTarget> targets;
  for (const Staged& s : staged_) {
    std::error_code ec;
    if (s.directory) {
      write_marker(s.temp);
      targets.push_back(report_target(s.path));
    } else {
      if (fs::is_directory(s.path, ec)) fail(s.path, "cannot write: it is a directory");
      targets.push_back(ReportTarget::New);
    }
  }
  // The renames, one by one. What each one replaces is kept aside until all have succeeded (an old file as a hard
  // link, an old report directory renamed), so that a rename failing halfway (a directory removed meanwhile) puts
  // every destination back as it was: all the outputs or none.
  struct Done {
    std::size_t index;
    fs::path aside;          // what the destination held, set aside ("" if nothing, or an empty directory)
    bool empty_dir = false;  // the destination was an empty directory (rename(2) replaced it)
  };
  std::vector<Done> done;
  const auto undo = [&] {
    for (auto it = done.rbegin(); it != done.rend(); ++it) {
      const Staged& s = staged_[it->index];
      std::error_code ec;
      fs::rename(s.path, s.temp, ec);  // the new output back to its temporary, which the destructor removes
      if (!it->aside.empty()) fs::rename(it->aside, s.path, ec);
      else if (it->empty_dir) fs::create_directory(s.path, ec);
    }
  };
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    const Staged& s = staged_[i];
    const fs::path destination = s.path;
    std::error_code ec;
    Done d{i, {}, false};
    if (s.directory && targets[i] == ReportTarget::Mbgen) {
      d.aside = temp_for(destination, "old");
      fs::rename(destination, d.aside, ec);
      if (ec) {
        undo();
        fail(destination, "cannot replace the old report: " + ec.message());
      }
    } else if (s.directory) {
      d.empty_dir = targets[i] == ReportTarget::Empty;
    } else if (fs::exists(fs::symlink_status(destination, ec))) {
      d.aside = temp_for(destination, "old");
      if (::link(destination.c_str(), d.aside.c_str()) != 0) d.aside.clear();  // no hard links here: not restorable
    }
    fs::rename(s.temp, destination, ec);  // over an empty directory too (rename(2) replaces it)
    if (ec) {
      std::error_code back;
      if (s.directory && !d.aside.empty()) fs::rename(d.aside, destination, back);
      else if (!d.aside.empty()) fs::remove(d.aside, back);
      undo();
      fail(destination, std::string(s.directory ? "cannot move the report into place: "
                                                : "cannot move the output into place: ") +
                            ec.message());
    }
    done.push_back(d);
  }
  // Then the destinations written through (devices, pipes, links), which cannot be staged: one failing undoes the
  // renames, though what it had written to its device stays written.
  for (const Through& t : through_) {
    try {
      write_file(t.path, t.content, t.path);
    } catch (...) {
      undo();
      throw;
    }
  }
  for (const Done& d : done) {  // all in place: what they replaced goes
    std::error_code ec;
    if (!d.aside.empty()) fs::remove_all(d.aside, ec);
  }
  for (const std::string& path : removed_) {
    std::error_code ec;
    if (!fs::remove(path, ec) && ec) fail(path, "cannot remove this stale output: " + ec.message());
  }
  for (const std::string& chunk : stdout_chunks_) std::cout << chunk;
  std::cout.flush();
  committed_ = true;
  if (!stdout_chunks_.empty()) require_standard_output_written();
}

void require_standard_output_written() {
  errno = 0;
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (!failed) return;
  const int error = errno;
  std::cout.clear();
  throw OutputError("mbgen: error: writing to standard output failed" +
                    (error != 0 ? std::string(": ") + std::strerror(error) : std::string()) +
                    "; what was written there is incomplete");
}

}  // namespace mbgen::cli
