// read_data_file: dispatch on the CSV header and on UFF name or content, the sidecar mapping file, and
// the errors for files of no known kind.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "mbgen_test/files.hpp"

#include "mbgen/data/data_error.hpp"
#include "mbgen/data/data_set.hpp"
#include "mbgen_test/paths.hpp"

using namespace mbgen;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir() { return mbgen::test::test_dir("data_set_test"); }

std::string write(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

std::string sample(const std::string& name) { return std::string(mbgen_test_data_dir()) + "/uff/" + name; }

// Standard input as the reader sees it: no seeking, bytes in pieces of `piece`. Serves `text`, or with an empty text
// `endless` zero bytes (a pipe from /dev/zero, ended here so that a reader that reads everything still stops), and
// counts what it served.
class Pipe : public std::streambuf {
 public:
  Pipe(std::string text, std::size_t piece, std::size_t endless = 0)
      : text_(std::move(text)), piece_(piece), endless_(endless) {}
  std::size_t served() const { return served_; }

 protected:
  int_type underflow() override {
    const std::size_t total = text_.empty() ? endless_ : text_.size();
    const std::size_t n = std::min(piece_, total - served_);
    if (n == 0) return traits_type::eof();
    buffer_.assign(n, '\0');
    if (!text_.empty()) buffer_.assign(text_, served_, n);
    served_ += n;
    setg(buffer_.data(), buffer_.data(), buffer_.data() + n);
    return traits_type::to_int_type(buffer_[0]);
  }

 private:
  std::string text_, buffer_;
  std::size_t piece_, endless_, served_ = 0;
};

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace

TEST_CASE("CSV kinds are told by the first header column") {
  const auto time = read_data_file(write("a.csv", "# set k=2\nt,F,x\n0,1,2\n0.5,1,2\n"), {"F"}, {"x"});
  REQUIRE(std::holds_alternative<TimeRecord>(time.content));
  CHECK(std::get<TimeRecord>(time.content).samples() == 2);
  CHECK(time.set().at("k").value == 2);
  CHECK(time.file().find("a.csv") != std::string::npos);

  const auto frf = read_data_file(write("b.txt", "\n# FRF\nf_hz,x/F.re,x/F.im\n1,2,3\n"));
  REQUIRE(frf.is_frf());
  CHECK(std::get<FrfData>(frf.content).channels.at(0).values[0] == std::complex<double>(2, 3));

  CHECK_THROWS_WITH(read_data_file(write("c.csv", "# x\nfreq,a\n1,2\n")),
                    Catch::Contains("c.csv:2:1: error: cannot tell the kind of data: the header starts with 'freq'"));
  CHECK_THROWS_WITH(read_data_file(write("d.csv", "")), Catch::Contains("d.csv: error: empty file"));
  CHECK_THROWS_WITH(read_data_file(write("e.csv", "t,F,y\n0,1,2\n1,1,2\n"), {"F"}, {"x"}),
                    Catch::Contains("column 'y' is neither a model input nor output"));
  CHECK_THROWS_WITH(read_data_file((temp_dir() / "missing.csv").string()), Catch::Contains("cannot open file"));
}

TEST_CASE("streams: standard-input style reading") {
  std::istringstream in("t,F\n0,1\n1,2\n");
  CHECK(std::holds_alternative<TimeRecord>(read_data(in, "-").content));
  // UFF recognised by content when the name says nothing.
  std::ifstream uff(sample("non_ascii_header.uff"), std::ios::binary);
  const auto set = read_data(uff, "-");
  REQUIRE(std::holds_alternative<FrfData>(set.content));
  CHECK(std::get<FrfData>(set.content).f_hz.size() == 6);
}

TEST_CASE("standard input and UFF files are read as they come, never whole") {
  // `--data -` from /dev/zero, and a UFF file that is /dev/zero: both were read whole before a line was looked at,
  // until the memory ran out. Now a line is refused past 16 MiB, when little more than that has been read.
  const std::size_t endless = std::size_t(64) << 20;
  for (const std::string name : {"-", "zero.uff"}) {
    Pipe zeros("", 1 << 16, endless);
    std::istream in(&zeros);
    CHECK_THROWS_WITH(read_data(in, name), name + ":1: error: line longer than 16 MiB");
    CHECK(zeros.served() < (std::size_t(17) << 20));
  }
  // Every kind through a pipe in odd pieces: told from its first lines, which are read again, then parsed as a file.
  for (const std::size_t piece : {std::size_t(1), std::size_t(7), std::size_t(4096)}) {
    INFO("pieces of " << piece);
    Pipe csv("\xEF\xBB\xBF# set m=2\nt,F\n0,1\n1,2\n", piece);
    std::istream csv_in(&csv);
    const DataSet record = read_data(csv_in, "-");
    REQUIRE(std::holds_alternative<TimeRecord>(record.content));
    CHECK(std::get<TimeRecord>(record.content).signals.at(0).values[1] == 2);
    CHECK(record.set().at("m").line == 1);
    for (const char* name : {"non_ascii_header.uff", "Sample_UFF58b_bin.uff", "binary8byte.uff"}) {
      INFO(name);
      const DataSet expected = read_data_file(sample(name));
      Pipe uff(file_text(sample(name)), piece);
      std::istream uff_in(&uff);
      const DataSet got = read_data(uff_in, "-");
      REQUIRE(got.content.index() == expected.content.index());
      if (const auto* f = std::get_if<FrfData>(&got.content)) {
        const FrfData& e = std::get<FrfData>(expected.content);
        CHECK(f->f_hz == e.f_hz);
        CHECK(f->channels.at(0).values == e.channels.at(0).values);
      } else {
        const TimeRecord& t = std::get<TimeRecord>(got.content);
        const TimeRecord& e = std::get<TimeRecord>(expected.content);
        CHECK(t.t == e.t);
        CHECK(t.signals.at(0).values == e.signals.at(0).values);
      }
    }
  }
}

TEST_CASE("UFF files, with the sidecar mapping PATH.map or an explicit one") {
  // A copy of a sample time history, with a mapping file beside it.
  std::ifstream src(sample("time-history-not-all-columns-filled.uff"), std::ios::binary);
  std::stringstream bytes;
  bytes << src.rdbuf();
  const std::string path = write("th.uff", bytes.str());
  fs::remove(path + ".map");
  CHECK_THROWS_WITH(read_data_file(path, {"F"}, {"acc"}), Catch::Contains("'0:S = NAME'"));
  write("th.uff.map", "# mapping\n0:S = acc\nset n_sp=300\nhold=none\n");
  const auto set = read_data_file(path, {"F"}, {"acc"});
  const TimeRecord& rec = std::get<TimeRecord>(set.content);
  CHECK(rec.signals.at(0).name == "acc");
  CHECK(rec.hold == HoldMode::None);
  CHECK(rec.set.at("n_sp").text == "300");
  // An explicit mapping wins over the sidecar.
  UffMapping explicit_map;
  explicit_map.names["0:S"] = "mic";
  const auto other = read_data_file(path, ChannelNames{{"F"}, {"mic"}}, explicit_map);
  CHECK(std::get<TimeRecord>(other.content).signals.at(0).name == "mic");
  // The shared samples are read by extension.
  CHECK(std::holds_alternative<TimeRecord>(read_data_file(sample("binary8byte.uff")).content));
  CHECK_THROWS_WITH(read_data_file(sample("dataset_milestone_in_header.uff")), Catch::Contains("cut off"));
}

TEST_CASE("a line is read up to 16 MiB, and lines of any other length as they are") {
  // `--data /dev/zero` (no newline ever) grew one line until the memory ran out.
  std::istringstream endless("f_hz," + std::string((std::size_t(16) << 20) + 1, '0'));
  CHECK_THROWS_WITH(read_data(endless, "zero.csv"), "zero.csv:1: error: line longer than 16 MiB");
  // Lines at and around the reader's 64 KiB buffer, with and without a final newline, CRLF, empty lines.
  for (const std::size_t width : {std::size_t(65534), std::size_t(65535), std::size_t(65536), std::size_t(200000)}) {
    const std::string comment = "# " + std::string(width - 2, 'c');
    for (const char* end : {"\n", "\r\n", ""}) {
      std::istringstream in(comment + "\n\nf_hz,y/F.re,y/F.im\r\n1,2,3\n\n2,4,5" + end);
      const DataSet d = read_data(in, "wide.csv");
      const FrfData& f = std::get<FrfData>(d.content);
      INFO("width " << width << ", end `" << end << "`");
      REQUIRE(f.f_hz.size() == 2);
      CHECK(f.channels.at(0).values[1] == std::complex<double>(4, 5));
    }
  }
}
