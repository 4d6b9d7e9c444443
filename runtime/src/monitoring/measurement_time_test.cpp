// `# time=` lines: their form, their value, and the order they give.
#include "mbgen/data/data_error.hpp"
#include "mbgen_test/files.hpp"
#include "mbgen/monitoring/measurement_time.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace mbgen;

TEST_CASE("ISO 8601 times are read as UTC seconds", "[monitor]") {
  CHECK(parse_measurement_time("1970-01-01T00:00:00Z")->seconds == 0);
  CHECK(parse_measurement_time("2026-03-07T08:00:00Z")->seconds == 1772870400);
  CHECK(parse_measurement_time("2026-03-07T09:00:00+01:00")->seconds == 1772870400);
  CHECK(parse_measurement_time("2026-03-07")->seconds == 1772841600);
  CHECK(parse_measurement_time("2026-03-07T08:00")->seconds == 1772870400);
  CHECK(parse_measurement_time("2026-03-07T08:00:00.25Z")->seconds == Approx(1772870400.25));
  CHECK(parse_measurement_time("2024-02-29T00:00:00Z"));
  CHECK_FALSE(parse_measurement_time("2026-02-29T00:00:00Z"));
  CHECK_FALSE(parse_measurement_time("2026-13-01"));
  CHECK_FALSE(parse_measurement_time("2026-03-07 08:00"));
  CHECK_FALSE(parse_measurement_time("yesterday"));
  CHECK_FALSE(parse_measurement_time("2026-03-07T08:00:00Zjunk"));
}

TEST_CASE("the time line is read from a CSV preamble and orders the data sets", "[monitor]") {
  const auto dir = mbgen::test::test_dir("measurement_time_test");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  const std::string a = write("a.csv", "# a note\n# time = 2026-03-08T08:00:00Z\nf_hz,d1/F1.re,d1/F1.im\n1,2,3\n");
  const std::string b = write("b.csv", "# set m1=2\n#time=2026-03-07T08:00:00Z\n\nf_hz,d1/F1.re,d1/F1.im\n1,2,3\n");
  const std::string none = write("none.csv", "f_hz,d1/F1.re,d1/F1.im\n# time=2026-03-07T08:00:00Z\n");
  const std::string bad = write("bad.csv", "# time=March 7\nf_hz,d1/F1.re,d1/F1.im\n");
  const std::string twice = write("twice.csv", "# time=2026-03-07\n# time=2026-03-08\nf_hz,x\n");
  CHECK(read_measurement_time(a)->text == "2026-03-08T08:00:00Z");
  CHECK(read_measurement_time(b)->text == "2026-03-07T08:00:00Z");
  CHECK_FALSE(read_measurement_time(none));  // after the header it is no time line
  CHECK_THROWS_AS(read_measurement_time(bad), DataError);
  CHECK_THROWS_AS(read_measurement_time(twice), DataError);
  CHECK_FALSE(read_measurement_time("-"));

  const std::vector<std::string> paths = {a, b, a};
  const auto times = std::vector<std::optional<MeasurementTime>>{read_measurement_time(a), read_measurement_time(b),
                                                                 read_measurement_time(a)};
  CHECK(time_order(paths, times) == std::vector<std::size_t>{1, 0, 2});
  CHECK(time_order({none, none}, {std::nullopt, std::nullopt}) == std::vector<std::size_t>{0, 1});
  CHECK_THROWS_AS(time_order({a, none}, {times[0], std::nullopt}), DataError);
  std::filesystem::remove_all(dir);
}
