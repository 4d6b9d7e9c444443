// valid_utf8: a channel or file name in another encoding made gnuplot's SVG not well-formed XML (the report's image
// broken) and report.md/report.html invalid UTF-8.
#include <catch2/catch.hpp>

#include "text/utf8.hpp"

namespace mbgen {

TEST_CASE("valid_utf8 keeps UTF-8 and replaces every other byte by U+FFFD", "[text][utf8]") {
  const std::string fffd = "\xEF\xBF\xBD";
  CHECK(valid_utf8("") == "");
  CHECK(valid_utf8("d1/F1 \xCE\xB6 \xE2\x80\x94 \xF0\x9F\x98\x80") == "d1/F1 \xCE\xB6 \xE2\x80\x94 \xF0\x9F\x98\x80");
  CHECK(valid_utf8("y\xFF/F") == "y" + fffd + "/F");
  CHECK(valid_utf8("caf\xE9.csv") == "caf" + fffd + ".csv");   // Latin-1
  CHECK(valid_utf8("\xC0\xAF") == fffd + fffd);                // an overlong '/'
  CHECK(valid_utf8("\xED\xA0\x80") == fffd + fffd + fffd);     // a surrogate
  CHECK(valid_utf8("\xE2\x80") == fffd + fffd);                // cut off at the end
  CHECK(valid_utf8("\xF4\x90\x80\x80") == fffd + fffd + fffd + fffd);  // above U+10FFFF
}

}  // namespace mbgen
