// UFF 58/58b: every sample file of tests/data/uff (copied from the shared samples), small fixtures written here (uneven abscissa,
// big endian, run-together numbers, other datasets), the mapping to model channels, and clear errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mbgen/data/data_error.hpp"
#include "mbgen/data/data_set.hpp"
#include "mbgen/data/uff.hpp"
#include "mbgen_test/paths.hpp"

using namespace mbgen;
namespace fs = std::filesystem;

namespace {

std::string sample(const std::string& name) { return std::string(mbgen_test_data_dir()) + "/uff/" + name; }

std::vector<Uff58Record> read_text(const std::string& text) {
  std::istringstream in(text);
  return read_uff58(in, "fix.uff");
}

std::string uff_error(const std::string& text) {
  try {
    read_text(text);
  } catch (const DataError& e) {
    return e.what();
  }
  FAIL("no DataError for:\n" << text);
  return {};
}

// Header lines 1..11 of a dataset 58 (records 1 to 11) in the fixed-width layout of the standard.
std::string header(int function_type, int rsp_node, int rsp_dir, int ref_node, int ref_dir, int data_type,
                   int points, int even, double xmin, double dx, int abscissa_type = 18) {
  char r6[128], r7[128], r8[128];
  std::snprintf(r6, sizeof r6, "%5d%10d%5d%10d %-10s%10d%4d %-10s%10d%4d\n", function_type, 0, 0, 0, "pt", rsp_node,
                rsp_dir, "pt", ref_node, ref_dir);
  std::snprintf(r7, sizeof r7, "%10d%10d%10d%13.5E%13.5E%13.5E\n", data_type, points, even, xmin, dx, 0.0);
  std::snprintf(r8, sizeof r8, "%10d%5d%5d%5d %-20s %-20s\n", abscissa_type, 0, 0, 0, "Frequency", "Hz");
  return std::string("id1\nid2\nid3\nid4\nid5\n") + r6 + r7 + r8 +
         "        12    0    0    0 Acceleration         m/s^2               \n"
         "        13    0    0    0 Force                N                   \n"
         "         0    0    0    0 NONE                 NONE                \n";
}

}  // namespace

TEST_CASE("sample: non-ASCII header, complex single-precision FRF") {
  const auto records = read_uff58(sample("non_ascii_header.uff"));
  REQUIRE(records.size() == 1);
  const Uff58Record& r = records[0];
  CHECK_FALSE(r.binary);
  CHECK(r.line == 2);
  CHECK(r.id[0] == "ref6_23_Mar");
  CHECK(r.id[4] == "H1 : #  2 / #  1");
  CHECK(r.function_type == 4);
  CHECK(r.ordinate_data_type == 5);
  CHECK(r.is_complex());
  CHECK(r.even_spacing);
  CHECK(r.abscissa_type == 18);
  CHECK(r.abscissa_units == "Hz");
  // The units hold a Latin-1 superscript two (byte 0xB2): kept as it is.
  CHECK(r.ordinate_units == "(1/N)*(m/s\xb2)");
  REQUIRE(r.points == 6);
  REQUIRE(r.x.size() == 6);
  CHECK(r.x[0] == 0.0);
  CHECK(r.x[5] == Approx(5 * 1.95313e-01).epsilon(1e-12));
  CHECK(r.y[0] == std::complex<double>(4.07994e-01, 0.0));
  CHECK(r.y[1] == std::complex<double>(-5.99924e-02, -5.53260e-02));
  CHECK(r.y[5] == std::complex<double>(3.75037e+00, 2.93363e+00));

  // Nodes and directions are 0 in this file: scalar point 0, default names.
  const auto set = uff_to_data_set(records, "non_ascii_header.uff", UffMapping{});
  const FrfData& frf = std::get<FrfData>(set.content);
  REQUIRE(frf.channels.size() == 1);
  CHECK(frf.channels[0].output == "node0:S");
  CHECK(frf.channels[0].input == "node0:S");
  CHECK(frf.f_hz == r.x);
  CHECK(frf.channels[0].values == r.y);
}

TEST_CASE("sample: time history with a short last line and three-digit exponents") {
  const auto records = read_uff58(sample("time-history-not-all-columns-filled.uff"));
  REQUIRE(records.size() == 1);
  const Uff58Record& r = records[0];
  CHECK(r.function_type == 1);
  CHECK(r.ordinate_data_type == 2);
  CHECK_FALSE(r.is_complex());
  CHECK(r.abscissa_increment == 5e-5);
  CHECK(r.abscissa_type == 17);
  CHECK(r.id[0].substr(0, 7) == "1x : m/");  // UTF-8 superscript follows
  REQUIRE(r.points == 13);
  CHECK(r.x[12] == Approx(12 * 5e-5).epsilon(1e-12));
  CHECK(r.y[0].real() == -3.81956);
  CHECK(r.y[6].real() == -3.90210);
  CHECK(r.y[12].real() == -5.84096);
  CHECK(r.y.imag().isZero(0));

  UffMapping map;
  map.names["0:S"] = "acc";
  map.set["n_sp"] = SetValue{"300", 300};
  const auto set = uff_to_data_set(records, "th.uff", map, ChannelNames{{"F"}, {"acc"}});
  const TimeRecord& rec = std::get<TimeRecord>(set.content);
  CHECK(rec.hold == HoldMode::ZeroOrder);
  CHECK(rec.set.at("n_sp").value == 300);
  REQUIRE(rec.signals.size() == 1);
  CHECK(rec.signals[0].name == "acc");
  CHECK(rec.dt() == Approx(5e-5));
  CHECK(rec.at("acc").values[12] == -5.84096);
  // Unmapped, the default name is not a model channel: the message says how to map it.
  CHECK_THROWS_WITH(uff_to_data_set(records, "th.uff", UffMapping{}, ChannelNames{{"F"}, {"acc"}}),
                    Catch::Contains("th.uff:2: error: UFF time response point 0:S ('node0:S') is neither") &&
                        Catch::Contains("outputs: acc") && Catch::Contains("'0:S = NAME'"));
}

TEST_CASE("sample: header declaring more samples than the file holds is rejected") {
  CHECK_THROWS_WITH(read_uff58(sample("dataset_milestone_in_header.uff")),
                    Catch::Contains("dataset_milestone_in_header.uff:2: error: UFF dataset 58 is cut off") &&
                        Catch::Contains("declares 2508876 points") && Catch::Contains("holds 42 values"));
}

TEST_CASE("sample: 58b binary, single precision, 79 292 samples") {
  const auto records = read_uff58(sample("Sample_UFF58b_bin.uff"));
  REQUIRE(records.size() == 1);
  const Uff58Record& r = records[0];
  CHECK(r.binary);
  CHECK(r.function_type == 1);
  CHECK(r.response_entity == "Mic 01");
  CHECK(r.response_node == 0);
  CHECK(r.response_direction == 1);
  CHECK(r.ordinate_data_type == 2);
  CHECK(r.ordinate_label == "Pressure");
  REQUIRE(r.points == 79292);
  CHECK(r.x[79291] == Approx(79291 * 1.52588e-05).epsilon(1e-12));
  // Expected values read from the bytes with Python's struct module ('<f').
  CHECK(r.y[0].real() == static_cast<double>(-0.014755260199308395f));
  CHECK(r.y[1].real() == static_cast<double>(-0.017295705154538155f));
  CHECK(r.y[79291].real() == static_cast<double>(-0.004314688965678215f));
  const auto set = uff_to_data_set(records, "s.uff", UffMapping{});
  CHECK(std::get<TimeRecord>(set.content).signals.at(0).name == "node0:+X");
}

TEST_CASE("sample: 58b binary, double precision: a 5 Hz sine") {
  const auto records = read_uff58(sample("binary8byte.uff"));
  REQUIRE(records.size() == 1);
  const Uff58Record& r = records[0];
  CHECK(r.binary);
  CHECK(r.ordinate_data_type == 4);
  CHECK(r.response_entity == "sine 5 Hz");
  CHECK(r.response_node == 1);
  CHECK(r.response_direction == 0);
  REQUIRE(r.points == 250);
  CHECK(r.abscissa_increment == 0.01);
  // sin(2 pi 5 t) at t = k / 100; the writer's values carry single-precision rounding (about 7e-6).
  for (Eigen::Index k = 0; k < r.points; ++k) CHECK(r.y[k].real() == Approx(std::sin(M_PI * k / 10.0)).margin(1e-5));
  CHECK(r.y[0].real() == 0.0);
}

TEST_CASE("fixture: ASCII complex double, uneven abscissa, run-together numbers, D exponents, other datasets") {
  const std::string text =
      "    -1\n   164\n         1  SI\n    1.0D+00    1.0D+00    1.0D+00\n    -1\n"
      "    -1\n    58\n" +
      header(4, 3, 3, 7, -2, 6, 2, 0, 0.0, 0.0) +
      "  1.00000E+01  1.500000000000E+00 -2.500000000000E-01\n"
      "  2.50000E+01-1.000000000000D+00-3.000000000000E+00\n"
      "    -1\n"
      "    -1\n    58\n" +
      header(6, 3, 3, 7, -2, 2, 2, 0, 0.0, 0.0) + "  1.00000E+01  9.00000E-01  2.50000E+01  5.00000E-01\n    -1\n";
  const auto records = read_text(text);
  REQUIRE(records.size() == 2);
  const Uff58Record& r = records[0];
  CHECK(r.line == 7);
  CHECK(r.response_node == 3);
  CHECK(r.response_direction == 3);
  CHECK(r.reference_node == 7);
  CHECK(r.reference_direction == -2);
  CHECK_FALSE(r.even_spacing);
  REQUIRE(r.points == 2);
  CHECK(r.x[0] == 10.0);
  CHECK(r.x[1] == 25.0);
  CHECK(r.y[0] == std::complex<double>(1.5, -0.25));
  CHECK(r.y[1] == std::complex<double>(-1.0, -3.0));

  UffMapping map;
  map.names["3:+Z"] = "x1";
  map.names["7:-Y"] = "F";
  const auto set = uff_to_data_set(records, "fix.uff", map, ChannelNames{{"F"}, {"x1"}});
  const FrfData& frf = std::get<FrfData>(set.content);
  REQUIRE(frf.channels.size() == 1);
  CHECK(frf.channels[0].output == "x1");
  CHECK(frf.channels[0].input == "F");
  REQUIRE(frf.channels[0].coherence);
  CHECK((*frf.channels[0].coherence)[1] == 0.5);
  CHECK(frf.f_hz[1] == 25.0);
  // Without the mapping: default names, and the known-name check explains the mapping.
  CHECK_THROWS_WITH(uff_to_data_set(records, "fix.uff", UffMapping{}, ChannelNames{{"F"}, {"x1"}}),
                    Catch::Contains("fix.uff:7: error: UFF FRF response point 3:+Z ('node3:+Z') is not a model output") &&
                        Catch::Contains("'3:+Z = NAME'"));
}

TEST_CASE("fixture: 58b big endian, complex single precision, even abscissa") {
  const float values[] = {1.5f, -2.0f, 0.25f, 4.0f, -8.5f, 1e-3f};
  std::string body;
  for (float v : values) {
    unsigned char b[4];
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    for (int i = 0; i < 4; ++i) b[i] = static_cast<unsigned char>(bits >> (24 - 8 * i));
    body.append(reinterpret_cast<const char*>(b), 4);
  }
  const std::string text = "    -1\n    58b     2     2          11          24     0     0           0           0\n" +
                           header(4, 1, 1, 2, 3, 5, 3, 1, 5.0, 2.5) + body + "\n    -1\n";
  const auto records = read_text(text);
  REQUIRE(records.size() == 1);
  const Uff58Record& r = records[0];
  CHECK(r.binary);
  REQUIRE(r.points == 3);
  CHECK(r.x[2] == 10.0);
  CHECK(r.y[0] == std::complex<double>(1.5, -2.0));
  CHECK(r.y[2] == std::complex<double>(-8.5, static_cast<double>(1e-3f)));
}

TEST_CASE("UFF errors are clear") {
  const std::string h = header(4, 1, 1, 2, 3, 5, 2, 1, 0.0, 1.0);
  CHECK_THAT(uff_error(""), Catch::Contains("fix.uff: error: empty file"));
  CHECK_THAT(uff_error("t,F\n0,1\n"), Catch::Contains("fix.uff:1:1: error: expected '    -1'"));
  CHECK_THAT(uff_error("    -1\n   164\n 1\n    -1\n"), Catch::Contains("no UFF dataset 58"));
  CHECK_THAT(uff_error("    -1\n    58\nid1\nid2\n    -1\n"),
             Catch::Contains("fix.uff:5: error: UFF dataset 58 ends after 2 of its 11 header lines"));
  CHECK_THAT(uff_error("    -1\n    58\n" + h + " 1.0 2.0 3.0\n    -1\n"),
             Catch::Contains("fix.uff:2: error: UFF dataset 58 is cut off: record 7 declares 2 points (4 values)") &&
                 Catch::Contains("holds 3 values"));
  CHECK_THAT(uff_error("    -1\n    58\n" + h + " 1.0 2.0 3.0 4.0 5.0\n    -1\n"),
             Catch::Contains("fix.uff:14:18: error: UFF 58 data: more values than the 4"));
  CHECK_THAT(uff_error("    -1\n    58\n" + h + " 1.0 2.0 x3 4.0\n    -1\n"),
             Catch::Contains("fix.uff:14:10: error: UFF 58 data: 'x3' is not a number"));
  CHECK_THAT(uff_error("    -1\n    58\n" + header(4, 1, 1, 2, 3, 3, 2, 1, 0.0, 1.0) + " 1 2\n    -1\n"),
             Catch::Contains("fix.uff:9:") && Catch::Contains("ordinate data type 3 is not supported"));
  std::string bad6 = h;
  bad6.replace(bad6.find("pt") + 10, 10, "       abc");  // the response node field (I10)
  CHECK_THAT(uff_error("    -1\n    58\n" + bad6 + " 1 2 3 4\n    -1\n"),
             Catch::Contains("fix.uff:8:42: error: UFF 58 record 6: response node 'abc' is not an integer"));
  CHECK_THAT(uff_error("    -1\n    58b     1     2          11          16     0     0           0           0\n" + h +
                       "12345678"),
             Catch::Contains("fix.uff:2: error: UFF dataset 58b is cut off: the header declares 16 bytes") &&
                 Catch::Contains("holds 8"));
  CHECK_THAT(uff_error("    -1\n    58b     1     2          11          12     0     0           0           0\n" + h +
                       "123456789012"),
             Catch::Contains("the header declares 12 bytes, but 2 points need 4 values of 4 bytes"));
  CHECK_THAT(uff_error("    -1\n    58b     1     1          11          16     0     0           0           0\n" + h),
             Catch::Contains("floating-point format 1 is not supported"));
  CHECK_THAT(uff_error("    -1\n  2414b\n"), Catch::Contains("binary UFF dataset 2414b is not supported"));
  // Lines are read as the CSV readers read them, at most 16 MiB each, with the line named (the file was read whole).
  CHECK_THAT(uff_error("    -1\n    58\n" + h + std::string((std::size_t(16) << 20) + 1, '1') + "\n    -1\n"),
             Catch::Equals("fix.uff:14: error: line longer than 16 MiB"));
}

TEST_CASE("UFF to data set: unsupported and mixed function types") {
  auto records = read_text("    -1\n    58\n" + header(2, 1, 1, 1, 1, 2, 2, 1, 0.0, 1.0) + " 1 2\n    -1\n");
  CHECK_THROWS_WITH(uff_to_data_set(records, "fix.uff", UffMapping{}),
                    Catch::Contains("fix.uff:2: error: UFF function type 2 (auto spectrum) is not supported"));
  auto mixed = read_text("    -1\n    58\n" + header(1, 1, 1, 0, 0, 2, 2, 1, 0.0, 1.0, 17) + " 1 2\n    -1\n" +
                         "    -1\n    58\n" + header(4, 1, 1, 2, 1, 5, 1, 1, 0.0, 1.0) + " 1 2\n    -1\n");
  CHECK_THROWS_WITH(uff_to_data_set(mixed, "fix.uff", UffMapping{}),
                    Catch::Contains("fix.uff:17: error: UFF file mixes time responses (first on line 2)"));
  auto coh_only = read_text("    -1\n    58\n" + header(6, 1, 1, 2, 1, 2, 2, 1, 0.0, 1.0) + " 0.5 0.5\n    -1\n");
  CHECK_THROWS_WITH(uff_to_data_set(coh_only, "fix.uff", UffMapping{}), Catch::Contains("coherences but no FRF"));
}

TEST_CASE("UFF mapping files") {
  std::istringstream in("# rig 3\n1:+X = xs_front\n  12:-RZ=phi\n0:S = mic\nset n_sp=300\nhold=none\n");
  const UffMapping m = read_uff_mapping(in, "map.txt");
  CHECK(m.names.at("1:+X") == "xs_front");
  CHECK(m.names.at("12:-RZ") == "phi");
  CHECK(m.names.at("0:S") == "mic");
  CHECK(m.set.at("n_sp").text == "300");
  CHECK(m.hold == HoldMode::None);
  CHECK(uff_channel_name(m, 12, -6) == "phi");
  CHECK(uff_channel_name(m, 2, 2) == "node2:+Y");
  CHECK(uff_point_key(5, -4) == "5:-RX");
  CHECK_THROWS_WITH(uff_direction_name(7), Catch::Contains("direction code 7"));

  auto error = [](const std::string& text) {
    std::istringstream s(text);
    try {
      read_uff_mapping(s, "map.txt");
    } catch (const DataError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error("1:+X = a\n1:+W = b\n"), Catch::Contains("map.txt:2:1: error: expected 'NODE:DIR = NAME'"));
  CHECK_THAT(error("1:+X = a\n1:+X = b\n"), Catch::Contains("map.txt:2:1: error: point 1:+X is mapped twice"));
  CHECK_THAT(error("1:+X = 9a\n"), Catch::Contains("map.txt:1:8: error: '9a' is not a channel name"));
  CHECK_THAT(error("set a\n"), Catch::Contains("map.txt:1: error: bad '# set' line"));
}

TEST_CASE("write_uff58 writes what read_uff58 reads back, in the specification's columns") {
  Uff58Record r;
  r.id = {"mbgen export mdof2.mdl", "d1/F1", "NONE", "NONE", "NONE"};
  r.function_type = 4;
  r.response_entity = "mbgen", r.reference_entity = "mbgen";
  r.response_node = 2, r.response_direction = -3, r.reference_node = 1001, r.reference_direction = 1;
  r.ordinate_data_type = 6;
  r.abscissa_type = 18, r.abscissa_label = "Frequency", r.abscissa_units = "Hz";
  r.ordinate_type = 8, r.ordinate_label = "Displacement", r.ordinate_units = "m";
  r.ordinate_denominator_type = 13, r.ordinate_denominator_label = "Force", r.ordinate_denominator_units = "N";
  const int n = 7;  // an odd count: the last data line holds one complex point
  r.x.resize(n);
  r.y.resize(n);
  for (int k = 0; k < n; ++k) {
    r.x[k] = 10 + 0.25 * k;
    r.y[k] = {std::sin(0.3 * k) * 1e-6, -std::cos(0.7 * k) * 3e-7};
  }
  for (bool even : {true, false}) {
    r.even_spacing = even;
    r.abscissa_min = even ? 10 : 0, r.abscissa_increment = even ? 0.25 : 0;
    std::ostringstream text;
    write_uff58(text, r);
    // Record 6 in its fixed columns: entity at 32, node at 42-51, direction at 52-55 (1-based).
    std::istringstream lines(text.str());
    std::string line;
    for (int i = 0; i < 8; ++i) std::getline(lines, line);
    CHECK(line.substr(31, 10) == "mbgen     ");
    CHECK(line.substr(41, 10) == "         2");
    CHECK(line.substr(51, 4) == "  -3");
    std::istringstream in(text.str());
    const std::vector<Uff58Record> back = read_uff58(in, "written.uff");
    REQUIRE(back.size() == 1);
    const Uff58Record& b = back[0];
    CHECK(b.id == r.id);
    CHECK(b.function_type == 4);
    CHECK(b.response_node == 2);
    CHECK(b.response_direction == -3);
    CHECK(b.reference_node == 1001);
    CHECK(b.even_spacing == even);
    CHECK(b.ordinate_type == 8);
    CHECK(b.ordinate_units == "m");
    CHECK(b.ordinate_denominator_type == 13);
    CHECK(b.abscissa_units == "Hz");
    REQUIRE(b.y.size() == n);
    for (int k = 0; k < n; ++k) {
      CHECK(b.x[k] == Approx(r.x[k]).epsilon(1e-12));
      CHECK(std::abs(b.y[k] - r.y[k]) <= 1e-12 * std::abs(r.y[k]) + 1e-30);
    }
  }
  CHECK(uff58_even_increment_exact(0.25));
  CHECK_FALSE(uff58_even_increment_exact(1.0 / 3));
  r.binary = true;
  std::ostringstream ignored;
  CHECK_THROWS_AS(write_uff58(ignored, r), std::invalid_argument);
}
