#include "cli/output_files.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

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
