// CSV time records and FRFs: round trips through files in a temporary directory, and every validation
// error with its file, line and column.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mbgen/data/csv.hpp"
#include "mbgen_test/files.hpp"

#include "mbgen/data/data_error.hpp"

using namespace mbgen;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir() { return mbgen::test::test_dir("csv_test"); }

// The message of the DataError that reading `text` as a time record (or FRF) throws; fails if none is thrown.
std::string time_error(const std::string& text, const std::optional<ChannelNames>& known = std::nullopt) {
  std::istringstream in(text);
  try {
    read_time_record_csv(in, "rec.csv", known);
  } catch (const DataError& e) {
    return e.what();
  }
  FAIL("no DataError for:\n" << text);
  return {};
}

std::string frf_error(const std::string& text, const std::optional<ChannelNames>& known = std::nullopt) {
  std::istringstream in(text);
  try {
    read_frf_csv(in, "frf.csv", known);
  } catch (const DataError& e) {
    return e.what();
  }
  FAIL("no DataError for:\n" << text);
  return {};
}

const ChannelNames kModel{{"F"}, {"x1", "x2"}};

}  // namespace

TEST_CASE("time record: parse settings, hold and signals") {
  std::istringstream in(
      "# measured on rig 3\n"
      "# set n_sp=300\n"
      "#set m_add = 0.75\n"
      "# hold=none\n"
      "t,F,x1\r\n"
      "0,1,-1e-3\n"
      "0.001, +2.5 ,2E-3\n"
      "\n"
      "0.002,3,0.5\n");
  const TimeRecord r = read_time_record_csv(in, "rec.csv", kModel);
  CHECK(r.file == "rec.csv");
  REQUIRE(r.set.size() == 2);
  CHECK(r.set.at("n_sp").text == "300");
  CHECK(r.set.at("n_sp").value == 300.0);
  CHECK(r.set.at("m_add").text == "0.75");
  CHECK(r.set.at("m_add").value == 0.75);
  CHECK(r.hold == HoldMode::None);
  REQUIRE(r.samples() == 3);
  CHECK(r.dt() == Approx(0.001));
  REQUIRE(r.signals.size() == 2);
  CHECK(r.signals[0].name == "F");
  CHECK(r.signals[0].values[1] == 2.5);
  CHECK(r.at("x1").values[0] == -1e-3);
  CHECK(r.at("x1").values[1] == 2e-3);
  CHECK(r.find("x2") == nullptr);
  CHECK_THROWS_WITH(r.at("x2"), Catch::Contains("no signal 'x2'") && Catch::Contains("F, x1"));
  CHECK_THROWS_WITH(require_inputs(r, {"F", "G"}), Catch::Contains("G"));
  CHECK_NOTHROW(require_inputs(r, {"F"}));
}

TEST_CASE("time record: default hold is zero-order") {
  std::istringstream in("t,u\n0,1\n0.5,2\n");
  CHECK(read_time_record_csv(in, "a.csv").hold == HoldMode::ZeroOrder);
}

TEST_CASE("time record: file round trip is exact") {
  TimeRecord r;
  r.file = "x";
  r.set["k1"] = SetValue{"1.5e6", 1.5e6};
  r.hold = HoldMode::None;
  const int n = 50;
  r.t.resize(n);
  Signal u{"F", Eigen::VectorXd(n)}, y{"x1", Eigen::VectorXd(n)};
  for (int k = 0; k < n; ++k) {
    r.t[k] = 0.1 + k / 3000.0;  // not exactly representable steps
    u.values[k] = std::sin(0.37 * k) / 7.0;
    y.values[k] = 1e-7 * std::cos(1.1 * k) + 1e3;
  }
  r.signals = {u, y};
  const fs::path path = temp_dir() / "round_trip_time.csv";
  {
    std::ofstream out(path);
    write_time_record_csv(out, r);
  }
  const TimeRecord back = read_time_record_csv(path.string(), kModel);
  CHECK(back.file == path.string());
  CHECK(back.hold == HoldMode::None);
  CHECK(back.set.at("k1").text == "1.5e6");
  CHECK(back.t == r.t);  // exact: shortest round-trip formatting
  REQUIRE(back.signals.size() == 2);
  CHECK(back.signals[0].name == "F");
  CHECK(back.signals[0].values == u.values);
  CHECK(back.signals[1].values == y.values);
}

TEST_CASE("FRF: parse channels and coherence, round trip") {
  std::istringstream in(
      "# set n_sp=0\n"
      "f_hz,x1/F.re,x1/F.im,x2/F.im,x2/F.re,x1/F.coh\n"
      "0,1,0,0,2,1\n"
      "10.5,0.5,-0.25,1e-3,-2,0.75\n");
  const FrfData f = read_frf_csv(in, "frf.csv", kModel);
  REQUIRE(f.f_hz.size() == 2);
  CHECK(f.f_hz[1] == 10.5);
  CHECK(f.set.at("n_sp").value == 0.0);
  REQUIRE(f.channels.size() == 2);
  CHECK(f.channels[0].output == "x1");
  CHECK(f.channels[0].input == "F");
  CHECK(f.channels[0].values[1] == std::complex<double>(0.5, -0.25));
  REQUIRE(f.channels[0].coherence);
  CHECK((*f.channels[0].coherence)[1] == 0.75);
  CHECK(f.find("x2", "F")->values[1] == std::complex<double>(-2, 1e-3));
  CHECK_FALSE(f.find("x2", "F")->coherence);
  CHECK(f.find("x2", "G") == nullptr);

  const fs::path path = temp_dir() / "round_trip_frf.csv";
  {
    std::ofstream out(path);
    write_frf_csv(out, f);
  }
  const FrfData back = read_frf_csv(path.string(), kModel);
  CHECK(back.f_hz == f.f_hz);
  REQUIRE(back.channels.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(back.channels[i].output == f.channels[i].output);
    CHECK(back.channels[i].values == f.channels[i].values);
    CHECK(back.channels[i].coherence.has_value() == f.channels[i].coherence.has_value());
  }
  CHECK(*back.channels[0].coherence == *f.channels[0].coherence);
}

TEST_CASE("time record errors name file, line and column") {
  CHECK_THAT(time_error(""), Catch::Contains("rec.csv: error: empty file"));
  CHECK_THAT(time_error("# only a comment\n"), Catch::Contains("rec.csv:1: error: no header row"));
  CHECK_THAT(time_error("t,F\n"), Catch::Contains("rec.csv:1: error: no data rows"));
  CHECK_THAT(time_error("x,F\n0,1\n"), Catch::Contains("rec.csv:1:1: error: the first column") &&
                                           Catch::Contains("'t'") && Catch::Contains("found 'x'"));
  CHECK_THAT(time_error("f_hz,F\n0,1\n"), Catch::Contains("this is an FRF file"));
  CHECK_THAT(time_error("t\n0\n1\n"), Catch::Contains("rec.csv:1: error: no signal columns"));
  CHECK_THAT(time_error("t,F,x1,F\n0,1,2,3\n"),
             Catch::Contains("rec.csv:1:4: error: duplicate column 'F' (also column 2)"));
  CHECK_THAT(time_error("t,,x1\n0,1,2\n"), Catch::Contains("rec.csv:1:2: error: empty column name"));
  CHECK_THAT(time_error("t,F,x1\n0,1,2\n0.1,1\n"),
             Catch::Contains("rec.csv:3:3: error: row has 2 fields, the header has 3"));
  CHECK_THAT(time_error("t,F,x1\n0,1,2\n0.1,1,2,4\n"),
             Catch::Contains("rec.csv:3:4: error: row has 4 fields, the header has 3"));
  CHECK_THAT(time_error("t,F,x1\n0,1,2\n0.1,1,2x\n"),
             Catch::Contains("rec.csv:3:3: error: '2x' is not a number in column 'x1'"));
  CHECK_THAT(time_error("t,F,x1\n0,1,2\n0.1,,2\n"),
             Catch::Contains("rec.csv:3:2: error: '' is not a number in column 'F'"));
  CHECK_THAT(time_error("t,F,x1\n0,1,2\n0.1,nan,2\n"),
             Catch::Contains("rec.csv:3:2: error: 'nan' is not finite") && Catch::Contains("column 'F'"));
  CHECK_THAT(time_error("t,F,x1\n0,1,2\n0.1,1,-inf\n"), Catch::Contains("rec.csv:3:3: error: '-inf' is not finite"));
  CHECK_THAT(time_error("t,F\n0,1\n0.1,1\n# late\n0.2,1\n"),
             Catch::Contains("rec.csv:4:1: error: comment lines are allowed only before the header"));
  CHECK_THAT(time_error("t,F\n0,1\n"), Catch::Contains("rec.csv:2:1: error: a time record needs at least 2"));
  CHECK_THAT(time_error("t,F\n0,1\n0.1,1\n0.1,1\n"),
             Catch::Contains("rec.csv:4:1: error: time 't' is not strictly increasing"));
  CHECK_THAT(time_error("t,F\n0,1\n0.2,1\n0.1,1\n"), Catch::Contains("rec.csv:4:1: error: time 't' is not strictly"));
  // A dropped sample: 0, 0.1, 0.3, 0.4 (grid 0, 0.133, ...).
  CHECK_THAT(time_error("t,F\n0,1\n0.1,1\n0.3,1\n0.4,1\n"),
             Catch::Contains("rec.csv:3:1: error: time 't' is not uniformly sampled"));
  // Jitter below the tolerance (0.1 % of dt) is accepted.
  std::istringstream jitter("t,F\n0,1\n0.1001,1\n0.2,1\n");
  CHECK_NOTHROW(read_time_record_csv(jitter, "j.csv"));
  CHECK_THAT(time_error("t,F,y\n0,1,2\n0.1,1,2\n", kModel),
             Catch::Contains("rec.csv:1:3: error: column 'y' is neither a model input nor output") &&
                 Catch::Contains("inputs: F; outputs: x1, x2"));
}

TEST_CASE("configuration line errors") {
  CHECK_THAT(time_error("# set n_sp\nt,F\n0,1\n1,1\n"), Catch::Contains("rec.csv:1: error: bad '# set' line"));
  CHECK_THAT(time_error("# set 3x=1\nt,F\n0,1\n1,1\n"), Catch::Contains("rec.csv:1: error: bad '# set' line"));
  CHECK_THAT(time_error("#\n# set a=1..2\nt,F\n0,1\n1,1\n"),
             Catch::Contains("rec.csv:2: error: bad '# set' line: value '1..2' of 'a'"));
  CHECK_THAT(time_error("# set a=nan\nt,F\n0,1\n1,1\n"), Catch::Contains("is not a finite decimal number"));
  CHECK_THAT(time_error("# set a=1\n# set a=2\nt,F\n0,1\n1,1\n"),
             Catch::Contains("rec.csv:2: error: parameter 'a' is set twice"));
  CHECK_THAT(time_error("# hold=foh\nt,F\n0,1\n1,1\n"), Catch::Contains("rec.csv:1: error: bad '# hold' line"));
  CHECK_THAT(time_error("# hold=none\n# hold=zoh\nt,F\n0,1\n1,1\n"),
             Catch::Contains("rec.csv:2: error: hold mode given twice (first on line 1)"));
  // Free comments that merely start with similar words are not configuration.
  std::istringstream in("# settings of the rig\n# holder: steel\nt,F\n0,1\n1,1\n");
  CHECK(read_time_record_csv(in, "c.csv").set.empty());
}

TEST_CASE("FRF errors name file, line and column") {
  CHECK_THAT(frf_error("t,x1/F.re,x1/F.im\n0,1,2\n"), Catch::Contains("frf.csv:1:1: error: the first column of an FRF"));
  CHECK_THAT(frf_error("f_hz,x1/F.re\n0,1\n"),
             Catch::Contains("frf.csv:1:2: error: missing column 'x1/F.im'"));
  CHECK_THAT(frf_error("f_hz,x1/F.im\n0,1\n"), Catch::Contains("frf.csv:1:2: error: missing column 'x1/F.re'"));
  CHECK_THAT(frf_error("f_hz,x1/F.coh\n0,1\n"), Catch::Contains("missing column 'x1/F.re'"));
  CHECK_THAT(frf_error("f_hz,x1/F.re,x1/F.im,x1/F.re\n0,1,2,3\n"), Catch::Contains("frf.csv:1:4: error: duplicate column"));
  CHECK_THAT(frf_error("f_hz,x1.re\n0,1\n"), Catch::Contains("frf.csv:1:2: error: column 'x1.re' is not of the form"));
  CHECK_THAT(frf_error("f_hz,x1/F.real\n0,1\n"), Catch::Contains("is not of the form"));
  CHECK_THAT(frf_error("f_hz,x1/F.re,x1/F.im\n-1,1,2\n"), Catch::Contains("frf.csv:2:1: error: negative frequency -1"));
  CHECK_THAT(frf_error("f_hz,x1/F.re,x1/F.im\n2,1,2\n1,1,2\n"),
             Catch::Contains("frf.csv:3:1: error: frequencies must be strictly increasing"));
  CHECK_THAT(frf_error("f_hz,x1/F.re,x1/F.im,x1/F.coh\n1,1,2,0.5\n2,1,2,1.01\n"),
             Catch::Contains("frf.csv:3:4: error: coherence 1.01 in column 'x1/F.coh' is outside [0, 1]"));
  CHECK_THAT(frf_error("f_hz,x1/F.re,x1/F.im,x1/F.coh\n1,1,2,-0.1\n"), Catch::Contains("outside [0, 1]"));
  CHECK_THAT(frf_error("f_hz,x1/F.re,x1/F.im\n1,1,inf\n"), Catch::Contains("frf.csv:2:3: error: 'inf' is not finite"));
  CHECK_THAT(frf_error("# hold=none\nf_hz,x1/F.re,x1/F.im\n1,1,1\n"),
             Catch::Contains("frf.csv:1: error: '# hold=' applies to time records only"));
  CHECK_THAT(frf_error("f_hz,x3/F.re,x3/F.im\n1,1,1\n", kModel),
             Catch::Contains("frf.csv:1:2: error: column 'x3/F.re': 'x3' is not a model output") &&
                 Catch::Contains("outputs: x1, x2"));
  CHECK_THAT(frf_error("f_hz,x1/G.re,x1/G.im\n1,1,1\n", kModel),
             Catch::Contains("'G' is not a model input (inputs: F;"));
  CHECK_THAT(frf_error("f_hz,F/x1.re,F/x1.im\n1,1,1\n", kModel), Catch::Contains("'F' is not a model output"));
}

TEST_CASE("missing file is a DataError") {
  CHECK_THROWS_AS(read_time_record_csv((temp_dir() / "does-not-exist.csv").string()), DataError);
  CHECK_THROWS_WITH(read_frf_csv((temp_dir() / "does-not-exist.csv").string()), Catch::Contains("cannot open file"));
}
