#include "mbgen/report/gnuplot.hpp"
#include "text/utf8.hpp"

#include <cerrno>
#include <string>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace mbgen {

namespace {

enum class Run { Ok, Failed, NotInstalled };

// Runs `gnuplot SCRIPT` with `dir` as its working directory, no shell between (a directory named with quotes or
// `;` is only a name), its output discarded.
Run run_gnuplot(const std::string& dir, const std::string& script) {
  posix_spawn_file_actions_t actions;
  if (posix_spawn_file_actions_init(&actions) != 0) return Run::Failed;
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::string program = "gnuplot", argument = script;
  char* argv[] = {program.data(), argument.data(), nullptr};
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error == ENOENT) return Run::NotInstalled;
  if (error != 0) return Run::Failed;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return Run::Failed;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? Run::Ok : Run::Failed;
}

}  // namespace

std::string gnuplot_string(std::string_view s) {
  std::string out = "'";
  for (const char c : valid_utf8(s)) {  // gnuplot copies titles into the SVG, which must be UTF-8 to be XML
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += ' ';  // a newline would end the command
    } else {
      out += c;
      if (c == '\'') out += '\'';  // '' is a quote inside a single-quoted gnuplot string
    }
  }
  return out + "'";
}

std::string render_gnuplot(const std::string& dir, const std::vector<std::string>& stems) {
  bool installed = true, rendered = true;
  for (const std::string& stem : stems) {
    const Run r = run_gnuplot(dir, stem + ".gp");
    if (r == Run::NotInstalled) {
      installed = rendered = false;
      break;
    }
    if (r == Run::Failed) rendered = false;
  }
  if (rendered) return "";
  return std::string("**The plots were not rendered** (") +
         (installed ? "gnuplot failed" : "gnuplot is not installed") +
         "): run `gnuplot NAME.gp` in this directory to draw them from the .dat files.";
}

}  // namespace mbgen
