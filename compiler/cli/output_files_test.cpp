#include "cli/output_files.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mbgen_test/files.hpp"

using namespace mbgen;
namespace fs = std::filesystem;

namespace {

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// The entries of `dir` whose names hold `.mbgen-` (temporaries, set-aside copies).
int leftovers(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".mbgen-") != std::string::npos) ++n;
  return n;
}

}  // namespace

TEST_CASE("outputs replace what was there whole, and leave nothing beside them", "[cli]") {
  const fs::path dir = test::test_dir("output_files_replace");
  fs::remove_all(dir);
  fs::create_directories(dir);
  write(dir / "a.txt", "old a\n");
  {
    cli::OutputFiles out;
    out.add((dir / "a.txt").string(), "new a\n");
    out.add((dir / "b.txt").string(), "new b\n");
    out.commit();
  }
  CHECK(test::read_text((dir / "a.txt").string()) == "new a\n");
  CHECK(test::read_text((dir / "b.txt").string()) == "new b\n");
  CHECK(leftovers(dir) == 0);
}

TEST_CASE("a rename failing halfway puts back every output already moved: all or none", "[cli]") {
  const fs::path dir = test::test_dir("output_files_halfway");
  fs::remove_all(dir);
  fs::create_directories(dir / "sub");
  write(dir / "a.txt", "old a\n");
  // An earlier report, which the new one would replace whole.
  {
    cli::OutputFiles out;
    write(fs::path(out.stage_directory((dir / "report").string())) / "report.md", "old report\n");
    out.commit();
  }
  {
    cli::OutputFiles out;
    out.add((dir / "a.txt").string(), "new a\n");
    out.add((dir / "new.txt").string(), "new\n");
    write(fs::path(out.stage_directory((dir / "report").string())) / "report.md", "new report\n");
    out.add((dir / "sub" / "c.txt").string(), "new c\n");
    fs::remove_all(dir / "sub");  // the last destination's directory disappears before the outputs are committed
    CHECK_THROWS_AS(out.commit(), cli::OutputError);
  }
  CHECK(test::read_text((dir / "a.txt").string()) == "old a\n");
  CHECK_FALSE(fs::exists(dir / "new.txt"));
  CHECK(test::read_text((dir / "report" / "report.md").string()) == "old report\n");
  CHECK(leftovers(dir) == 0);
}

TEST_CASE("a symbolic link or a named pipe as destination is written through, not replaced", "[cli]") {
  const fs::path dir = test::test_dir("output_files_through");
  fs::remove_all(dir);
  fs::create_directories(dir);
  // The user's link to a file: the file gets the output, the link stays (the rename replaced the link by a file).
  write(dir / "target.json", "old\n");
  fs::create_symlink("target.json", dir / "link.json");
  // A named pipe (as /dev/stdout or /dev/null are devices): written into, not replaced by a regular file. The
  // reader is opened first, without blocking, so that the writer's open succeeds.
  REQUIRE(::mkfifo((dir / "pipe").c_str(), 0600) == 0);
  const int reader = ::open((dir / "pipe").c_str(), O_RDONLY | O_NONBLOCK);
  REQUIRE(reader >= 0);
  {
    cli::OutputPlan plan;
    plan.files = {{"--json", (dir / "link.json").string()}, {"-o", (dir / "pipe").string()}};
    CHECK_NOTHROW(plan.check());
    cli::OutputFiles out;
    out.add((dir / "link.json").string(), "new\n");
    out.add((dir / "pipe").string(), "through the pipe\n");
    out.add((dir / "plain.txt").string(), "plain\n");
    out.commit();
  }
  CHECK(fs::is_symlink(fs::symlink_status(dir / "link.json")));
  CHECK(test::read_text((dir / "target.json").string()) == "new\n");
  CHECK(fs::is_fifo(fs::symlink_status(dir / "pipe")));
  char buffer[64] = {};
  const ssize_t n = ::read(reader, buffer, sizeof buffer);
  ::close(reader);
  CHECK(std::string(buffer, n > 0 ? static_cast<std::size_t>(n) : 0) == "through the pipe\n");
  CHECK(test::read_text((dir / "plain.txt").string()) == "plain\n");
  CHECK(leftovers(dir) == 0);
}
