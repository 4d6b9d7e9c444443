// Plot titles built on valid_utf8: a channel or file name in another encoding made gnuplot's SVG not well-formed XML
// (the report's image broken).
#include <catch2/catch.hpp>

#include "mbgen/report/gnuplot.hpp"

namespace mbgen {

TEST_CASE("gnuplot titles are UTF-8, quoted, on one line", "[report][utf8]") {
  CHECK(gnuplot_string("y\xFF/F") == "'y\xEF\xBF\xBD/F'");
  CHECK(gnuplot_string("O'Brien\nrun") == "'O''Brien run'");
}

}  // namespace mbgen
