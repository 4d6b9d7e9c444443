// detail::format: what std::printf prints, at any length (the private helper it replaced cut texts at 511 bytes, as
// a diagnosis finding naming long channel and file names would be).
#include "text/string_format.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

using mbgen::detail::format;

TEST_CASE("format prints what printf prints, whatever the length") {
  CHECK(format("%.4g", 1234567.0) == "1.235e+06");
  CHECK(format("%4zu %10.3f Hz  zeta %.4g  ", std::size_t(3), 94.05983, 5.5e-4) == "   3     94.060 Hz  zeta 0.00055  ");
  CHECK(format("\\x%02X", 7u) == "\\x07");
  CHECK(format("%s", "") == "");
  for (const std::size_t length : {std::size_t(255), std::size_t(256), std::size_t(511), std::size_t(512), std::size_t(5000)}) {
    const std::string name(length, 'n');
    const std::string text = format("channel %s (%s) at %.1f Hz", name.c_str(), "d.csv", 12.25);
    INFO("length " << length);
    CHECK(text == "channel " + name + " (d.csv) at 12.2 Hz");
  }
}
