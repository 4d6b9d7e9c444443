// mbgen: compile a model to C++ (`mbgen MODEL.mdl -o OUT.cpp`), or inspect, fit, diagnose, monitor it.
// Exit status: 0 success, 1 bad input (model, data, an output that must not be written), 2 bad usage, 3 internal
// error (docs/cli.md). Nothing is written on failure.
#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>

#include <fcntl.h>

#include "cli/commands.hpp"
#include "cli/output_files.hpp"
#include "cli/version.hpp"

namespace {

// A standard stream the caller closed (`mbgen ... >&-`) is opened on /dev/null the wrong way round, so that using
// it fails (and is reported) instead of the first file mbgen opens taking its descriptor and receiving its output.
void guard_standard_streams() {
  for (int fd = 0; fd <= 2; ++fd)
    if (::fcntl(fd, F_GETFD) == -1 && errno == EBADF) ::open("/dev/null", fd == 0 ? O_WRONLY : O_RDONLY);
}

// A command that succeeded but whose standard output was lost (a full disk, a closed stream) did not succeed.
int finish(int status) {
  if (status != 0) return status;  // its error is reported already
  try {
    mbgen::cli::require_standard_output_written();
  } catch (const mbgen::cli::OutputError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return status;
}

int dispatch(int argc, char** argv);

void print_usage() {
  std::cout << mbgen::cli::version_text() << ": a symbolic-to-numeric model compiler for mechanical systems\n\n"
               "usage:\n"
               "  mbgen MODEL.mdl -o OUT.cpp [--header OUT.hpp] [--namespace NS]   compile to C++\n"
               "  mbgen inspect MODEL.mdl [--format markdown|latex|json]          symbolic matrices, TFs, modes\n"
               "  mbgen fit MODEL.mdl --data FILE... [--json OUT] [--report DIR]  estimate parameters\n"
               "  mbgen diagnose MODEL.mdl --data FILE... [--json OUT] [--report DIR] [--extended OUT.mdl]\n"
               "                                                                  find and fix what the model misses\n"
               "  mbgen modal --data FILE... [--band LO:HI] [--model MODEL.mdl] [--json OUT] [--report DIR]\n"
               "                                                                  experimental modal analysis of FRFs\n"
               "  mbgen sensitivity MODEL.mdl [--global] [--sweep NAME=LO:HI:N] [--json OUT] [--report DIR]\n"
               "                                                                  how the modes depend on the parameters\n"
               "  mbgen monitor MODEL.mdl --data FILE... [--baseline N] [--json OUT] [--report DIR]\n"
               "                                                                  track parameters over time, detect changes\n"
               "  mbgen export MODEL.mdl [--what matrices|state-space|modes|frf] [--format json|csv] [-o OUT]\n"
               "                                                                  the model's numbers for another tool\n"
               "  mbgen convert DATA... -o OUT.uff|OUT.csv [--model MODEL.mdl]    measured data for another tool\n\n"
               "Run `mbgen COMMAND --help` for a command's options.\n";
}

}  // namespace

int main(int argc, char** argv) {
  guard_standard_streams();
  return finish(dispatch(argc, argv));
}

namespace {

int dispatch(int argc, char** argv) {
  if (argc < 2) {
    print_usage();
    return 2;
  }
  const std::string first = argv[1];
  if (first == "--help" || first == "-h") {
    print_usage();
    return 0;
  }
  if (first == "--version") {
    std::cout << mbgen::cli::version_text() << "\n";
    return 0;
  }
  if (first == "inspect") return mbgen::cli::run_inspect(argc - 1, argv + 1);
  if (first == "fit") return mbgen::cli::run_fit(argc - 1, argv + 1);
  if (first == "diagnose") return mbgen::cli::run_diagnose(argc - 1, argv + 1);
  if (first == "modal") return mbgen::cli::run_modal(argc - 1, argv + 1);
  if (first == "sensitivity") return mbgen::cli::run_sensitivity(argc - 1, argv + 1);
  if (first == "monitor") return mbgen::cli::run_monitor(argc - 1, argv + 1);
  if (first == "export") return mbgen::cli::run_export(argc - 1, argv + 1);
  if (first == "convert") return mbgen::cli::run_convert(argc - 1, argv + 1);
  return mbgen::cli::run_compile(argc, argv);
}

}  // namespace
