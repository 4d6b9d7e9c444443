// UFF 55 (modes at nodes) and 15 (nodes): what write_uff55/write_uff15 write, read_uff55/read_uff15 read back to the
// written precision (six significant digits) and write again byte for byte; files beside other datasets (58, 58b);
// and malformed records refused naming file and line.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "mbgen/data/data_error.hpp"
#include "mbgen/data/uff.hpp"
#include "mbgen/data/uff55.hpp"

using namespace mbgen;

namespace {

// `v` as E13.5 holds it.
double written(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%13.5E", v);
  return std::strtod(text, nullptr);
}

Uff55Record complex_mode() {
  Uff55Record r;
  r.id = {"mbgen test", "mode 2", "", "", ""};
  r.analysis_type = 3;
  r.mode_number = 2;
  r.eigenvalue = {-3.14159265, 2 * M_PI * 123.456789};
  r.nodes = {1, 7, 1001};
  r.values.resize(3, 3);
  using C = std::complex<double>;
  r.values << C(1, 0), C(0, 0), C(-0.25, 1e-3), C(2.5e-7, -3.125e-9), C(0, 1), C(0, 0), C(0, 0), C(-123456.789, 0.5),
      C(1e-120, -1e120);  // three-digit exponents run the fields together
  return r;
}

Uff55Record normal_mode_6dof() {
  Uff55Record r;
  r.analysis_type = 2;
  r.data_characteristic = 3;
  r.specific_data_type = 12;
  r.complex = false;
  r.mode_number = 1;
  r.frequency_hz = 47.25;
  r.modal_mass = 1.5;
  r.viscous_damping = 0.0125;
  r.nodes = {3};
  r.values.resize(1, 6);
  r.values << 1, -2, 3, -0.4, 0.5, -0.6;
  return r;
}

std::string text_of(const Uff55Record& r) {
  std::ostringstream out;
  write_uff55(out, r);
  return out.str();
}

std::vector<Uff55Record> read_text(const std::string& text) {
  std::istringstream in(text);
  return read_uff55(in, "modes.uff");
}

std::string error_of(const std::string& text) {
  try {
    read_text(text);
  } catch (const DataError& e) {
    return e.what();
  }
  FAIL("no DataError for:\n" << text);
  return {};
}

}  // namespace

TEST_CASE("uff55: a complex mode reads back as written and writes the same bytes again") {
  const Uff55Record mode = complex_mode();
  const std::string text = text_of(mode);
  const auto back = read_text(text);
  REQUIRE(back.size() == 1);
  const Uff55Record& r = back[0];
  CHECK(r.line == 2);
  CHECK(r.id[0] == "mbgen test");
  CHECK(r.id[2] == "NONE");
  CHECK(r.analysis_type == 3);
  CHECK(r.data_characteristic == 2);
  CHECK(r.specific_data_type == 8);
  CHECK(r.complex);
  CHECK(r.mode_number == 2);
  CHECK(r.eigenvalue.real() == written(mode.eigenvalue.real()));
  CHECK(r.eigenvalue.imag() == written(mode.eigenvalue.imag()));
  CHECK(r.f_hz() == Approx(123.456789).epsilon(1e-5));
  CHECK(r.zeta() == Approx(3.14159265 / std::abs(mode.eigenvalue)).epsilon(1e-5));
  CHECK(r.nodes == mode.nodes);
  REQUIRE(r.values.rows() == 3);
  REQUIRE(r.values.cols() == 3);
  for (Eigen::Index n = 0; n < 3; ++n)
    for (Eigen::Index k = 0; k < 3; ++k) {
      CHECK(r.values(n, k).real() == written(mode.values(n, k).real()));
      CHECK(r.values(n, k).imag() == written(mode.values(n, k).imag()));
    }
  CHECK(text_of(r) == text);
  // Every line within the 80 columns of the format.
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) CHECK(line.size() <= 80);
}

TEST_CASE("uff55: a real normal mode with six values per node") {
  const Uff55Record mode = normal_mode_6dof();
  const std::string text = text_of(mode);
  const auto back = read_text(text);
  REQUIRE(back.size() == 1);
  CHECK(back[0].analysis_type == 2);
  CHECK(!back[0].complex);
  CHECK(back[0].f_hz() == 47.25);
  CHECK(back[0].zeta() == 0.0125);
  CHECK(back[0].modal_mass == 1.5);
  CHECK(back[0].values.cols() == 6);
  CHECK(back[0].values(0, 5) == std::complex<double>(-0.6, 0));
  CHECK(text_of(back[0]) == text);
}

TEST_CASE("uff55: modes beside nodes (15) and FRFs (58) in one file") {
  std::ostringstream out;
  write_uff15(out, {{1, 0, 0, 0, {0.0, 0.5, -1.25}, 0}, {7, 0, 0, 0, {1e3, 0.0, 2.0}, 0}});
  Uff58Record frf;
  frf.function_type = 4;
  frf.ordinate_data_type = 6;
  frf.abscissa_min = 1;
  frf.abscissa_increment = 1;
  frf.x = Eigen::VectorXd::LinSpaced(3, 1, 3);
  frf.y = Eigen::VectorXcd::Constant(3, {1, -1});
  write_uff58(out, frf);
  write_uff55(out, complex_mode());
  write_uff55(out, normal_mode_6dof());
  const auto modes = read_text(out.str());
  REQUIRE(modes.size() == 2);
  CHECK(modes[0].mode_number == 2);
  CHECK(modes[1].mode_number == 1);
  std::istringstream in(out.str());
  const auto nodes = read_uff15(in, "modes.uff");
  REQUIRE(nodes.size() == 2);
  CHECK(nodes[0].node == 1);
  CHECK(nodes[0].xyz[2] == -1.25);
  CHECK(nodes[1].xyz[0] == 1e3);
  CHECK(nodes[1].line == 4);
  std::istringstream again(out.str());
  CHECK(read_uff58(again, "modes.uff").size() == 1);  // and the FRF reader skips the 55s and the 15
}

TEST_CASE("uff55: pyuff's layout (lower-case exponents, normal modes) reads") {
  // As pyuff's _write55 writes a normal mode: '%10i' fields, '%13.5e' reals.
  const std::string text =
      "    -1\n    55\nNONE\nNONE\nNONE\nNONE\nNONE\n"
      "         1         2         2         8         2         3\n"
      "         2         4         1         3\n"
      "  1.30000e+01  0.00000e+00  0.00000e+00  0.00000e+00\n"
      "         1\n  1.00000e+00 -5.00000e-01  2.50000e-01\n"
      "         2\n -1.00000e+00  5.00000e-01 -2.50000e-01\n"
      "    -1\n";
  const auto modes = read_text(text);
  REQUIRE(modes.size() == 1);
  CHECK(modes[0].mode_number == 3);
  CHECK(modes[0].load_case == 1);
  CHECK(modes[0].f_hz() == 13.0);
  CHECK(modes[0].nodes == std::vector<int>{1, 2});
  CHECK(modes[0].values(1, 2) == std::complex<double>(-0.25, 0));
}

TEST_CASE("uff55: malformed records are refused with file and line") {
  const std::string good = text_of(complex_mode());
  // Record 6 (line 8): a frequency response (analysis type 5) is not a mode.
  std::string t = good;
  t.replace(t.find("         3         2"), 20, "         5         2");
  CHECK_THAT(error_of(t), Catch::Contains("modes.uff:8") && Catch::Contains("analysis type 5 is not a mode"));
  // Values per node that the data characteristic does not have.
  t = good;
  t.replace(t.find("         5         3\n"), 21, "         5         4\n");
  CHECK_THAT(error_of(t), Catch::Contains("modes.uff:8") && Catch::Contains("4 values per node"));
  // A node number that is not an integer (line 11, the first record 9).
  t = good;
  t.replace(t.find("         1\n"), 11, "       1.5\n");
  CHECK_THAT(error_of(t), Catch::Contains("modes.uff:11") && Catch::Contains("is not an integer"));
  // A node's values cut off by the closing delimiter.
  t = good.substr(0, good.rfind("    -1\n"));
  t = t.substr(0, t.rfind('\n', t.size() - 2) + 1) + "    -1\n";
  CHECK_THAT(error_of(t), Catch::Contains("modes.uff:") && Catch::Contains("ends too early"));
  // A file without modes.
  CHECK_THAT(error_of("    -1\n    15\n         1         0         0         0  0.0  0.0  0.0\n    -1\n"),
             Catch::Contains("no UFF dataset 55"));
  // Not a number.
  t = good;
  t.replace(t.find(" 1.00000E+00"), 12, " 1.0000xE+00");
  CHECK_THAT(error_of(t), Catch::Contains("modes.uff:12") && Catch::Contains("not a finite number"));
}

TEST_CASE("uff82: trace lines read back as written, and the modes' and FRFs' readers skip them") {
  Uff82TraceLine long_line;  // 10 entries: two lines of record 3, a pen lift in the middle
  long_line.number = 1;
  long_line.colour = 8;
  long_line.id = "frame";
  long_line.nodes = {1, 2, 3, 4, 0, 5, 6, 7, 1001, 1};
  Uff82TraceLine pair;
  pair.number = 2;
  pair.nodes = {7, 3};
  std::ostringstream out;
  write_uff15(out, {{1, 0, 0, 0, {0.0, 0.5, -1.25}, 0}, {7, 0, 0, 0, {1e3, 0.0, 2.0}, 0}});
  write_uff82(out, long_line);
  write_uff82(out, pair);
  Uff58Record frf;
  frf.function_type = 4;
  frf.ordinate_data_type = 6;
  frf.abscissa_min = 1;
  frf.abscissa_increment = 1;
  frf.x = Eigen::VectorXd::LinSpaced(3, 1, 3);
  frf.y = Eigen::VectorXcd::Constant(3, {1, -1});
  write_uff58(out, frf);
  write_uff55(out, complex_mode());
  const std::string text = out.str();
  // The fixed columns of the specification: 3I10, the ID line, 8I10 then the rest.
  CHECK(text.find("    -1\n    82" + std::string(74, ' ') + "\n         1        10         8\nframe" +
                  std::string(75, ' ') + "\n         1         2         3         4         0         5         6"
                                         "         7\n      1001         1\n    -1\n") != std::string::npos);
  std::istringstream in(text);
  const auto traces = read_uff82(in, "geometry.uff");
  REQUIRE(traces.size() == 2);
  CHECK(traces[0].number == 1);
  CHECK(traces[0].colour == 8);
  CHECK(traces[0].id == "frame");
  CHECK(traces[0].nodes == long_line.nodes);
  CHECK(traces[0].line == 7);  // after the 15 (lines 1 to 5) and its opening delimiter
  CHECK(traces[1].id == "NONE");
  CHECK(traces[1].nodes == std::vector<int>{7, 3});
  std::ostringstream again;
  write_uff82(again, traces[0]);
  write_uff82(again, traces[1]);
  CHECK(text.find(again.str()) != std::string::npos);  // the same bytes again (but the empty ID, written NONE)
  CHECK(read_text(text).size() == 1);                   // the modes' reader skips the 82s
  std::istringstream frfs(text);
  CHECK(read_uff58(frfs, "geometry.uff").size() == 1);  // and so does the FRFs'
  std::istringstream nodes(text);
  CHECK(read_uff15(nodes, "geometry.uff").size() == 2);
  // A file with none has none.
  std::istringstream plain(text_of(complex_mode()));
  CHECK(read_uff82(plain, "modes.uff").empty());
}

TEST_CASE("uff82: malformed trace lines are refused with file and line, and writing checks its entries") {
  const auto error = [](const std::string& text) -> std::string {
    std::istringstream in(text);
    try {
      read_uff82(in, "geometry.uff");
    } catch (const DataError& e) {
      return e.what();
    }
    FAIL("no DataError for:\n" << text);
    return {};
  };
  CHECK_THAT(error("    -1\n    82\n         1         2\nNONE\n         1         2\n    -1\n"),
             Catch::Contains("geometry.uff:3") && Catch::Contains("UFF 82 record 1: expected 3 numbers"));
  CHECK_THAT(error("    -1\n    82\n         1         2         0\nNONE\n         1       2.5\n    -1\n"),
             Catch::Contains("geometry.uff:5") && Catch::Contains("is not an integer"));
  CHECK_THAT(error("    -1\n    82\n         1         2         0\nNONE\n         1        -3\n    -1\n"),
             Catch::Contains("geometry.uff:5") && Catch::Contains("a node number is >= 0"));
  CHECK_THAT(error("    -1\n    82\n         1         2         0\nNONE\n         1         2\n"),
             Catch::Contains("geometry.uff:2") && Catch::Contains("not closed"));
  std::ostringstream out;
  Uff82TraceLine t;
  t.nodes = {1};
  CHECK_THROWS_AS(write_uff82(out, t), std::invalid_argument);
  t.nodes = std::vector<int>(251, 1);
  CHECK_THROWS_AS(write_uff82(out, t), std::invalid_argument);
  t.nodes = {1, -2};
  CHECK_THROWS_AS(write_uff82(out, t), std::invalid_argument);
}
