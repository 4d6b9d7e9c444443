// The report document: its Markdown and HTML renderings, and what each does with a user's string.
#include "mbgen/report/report_document.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include "mbgen_test/paths.hpp"

using namespace mbgen;
using namespace mbgen::report;

namespace {

namespace fs = std::filesystem;

const std::string hostile = "a<script>alert(1)</script>&\"'|`*x*";

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(mbgen_binary_dir()) / "report_document_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("the Markdown rendering: blocks apart by a blank line, tables with empty cells", "[report]") {
  Document doc;
  doc.heading(1, Inline("Fit report: ") << code("m.mdl"));
  doc.paragraph(Inline("n = ") << 42 << ", x = " << 0.5 << ", **bold**");
  doc.list({"one", Inline("two ") << text("N/m")});
  doc.list({});  // nothing to list: no block
  doc.table({{"", "a", "b"}, {{"x", "1", ""}, {"y", Inline() << text("p|q"), "r|s"}}});
  doc.figure("set1_d1.svg", text("d1/F1"));
  CHECK(to_markdown(doc) ==
        "# Fit report: `m.mdl`\n\n"
        "n = 42, x = 0.5, **bold**\n\n"
        "- one\n- two N/m\n\n"
        "| | a | b |\n|---|---|---|\n| x | 1 | |\n| y | p\\|q | r\\|s |\n\n"
        "![d1/F1](set1_d1.svg)\n");
}

TEST_CASE("a user's string is literal in the Markdown", "[report]") {
  Document doc;
  doc.paragraph(Inline() << text(hostile) << " " << code(hostile));
  CHECK(to_markdown(doc) ==
        "a\\<script\\>alert(1)\\</script\\>\\&\"'\\|\\`\\*x\\* ``a<script>alert(1)</script>&\"'\\|`*x*``\n");
}

TEST_CASE("a table row needs a cell per column, and a figure a file the program made", "[report]") {
  Document doc;
  CHECK_THROWS_AS(doc.table({{"a", "b"}, {{"1"}}}), std::logic_error);
  CHECK_THROWS_AS(doc.figure("../x.svg", "x"), std::logic_error);
  CHECK_THROWS_AS(doc.figure("a b.svg", "x"), std::logic_error);
  CHECK_THROWS_AS(doc.heading(5, "x"), std::logic_error);
}

TEST_CASE("the HTML escapes every user string: text, code, figure alt and title", "[report][html]") {
  const fs::path dir = scratch("hostile");
  Document doc;
  doc.heading(1, Inline("Report: ") << code(hostile));
  doc.paragraph(Inline() << text(hostile));
  doc.list({Inline() << code(hostile)});
  doc.table({{Inline() << text(hostile)}, {{Inline() << code(hostile)}}});
  doc.figure("missing.svg", text(hostile));
  const std::string html = to_html(doc, dir.string());
  CHECK(html.find("<script") == std::string::npos);
  CHECK(html.find("alert(1)</") == std::string::npos);
  // In the title, h1, p, li, th, td and the figure's note.
  CHECK(count(html, "a&lt;script&gt;alert(1)&lt;/script&gt;&amp;&quot;&#39;|`*x*") == 7);
  CHECK(html.find("<title>Report: a&lt;script&gt;") != std::string::npos);
  // The missing plot is a note with its (escaped) alt text, not an image.
  CHECK(html.find("<img") == std::string::npos);
  CHECK(html.find("<figure class=\"missing\"><figcaption>a&lt;script&gt;") != std::string::npos);
  // Control characters show as the Markdown shows them.
  Document nl;
  nl.paragraph(Inline() << text("a\nb"));
  CHECK(to_html(nl, dir.string()).find("<p>a\\x0Ab</p>") != std::string::npos);
}

TEST_CASE("the HTML shows the program's Markdown as a renderer would", "[report][html]") {
  const fs::path dir = scratch("markup");
  const auto body = [&](const Inline& in) {
    Document doc;
    doc.paragraph(in);
    const std::string html = to_html(doc, dir.string());
    const std::size_t from = html.find("<p>") + 3;
    return html.substr(from, html.find("</p>", from) - from);
  };
  CHECK(body("**no**: at its upper bound") == "<strong>no</strong>: at its upper bound");
  CHECK(body("*(shared)*: x") == "<em>(shared)</em>: x");
  CHECK(body("the `shape` in the JSON") == "the <code>shape</code> in the JSON");
  CHECK(body("``a`b``") == "<code>a`b</code>");
  CHECK(body("`` `a ``") == "<code>`a</code>");
  CHECK(body("**data set 4** (`x`)") == "<strong>data set 4</strong> (<code>x</code>)");
  CHECK(body("5 * 3 * 2, a*") == "5 * 3 * 2, a*");  // no emphasis: the asterisks stand between blanks
  CHECK(body("a \\| b \\*c\\* \\\\x0A") == "a | b *c* \\x0A");
  CHECK(body("1 < 2 & \"q\"") == "1 &lt; 2 &amp; &quot;q&quot;");
  CHECK(body("unclosed `code") == "unclosed `code");
}

TEST_CASE("the HTML right-aligns the columns of numbers", "[report][html]") {
  const fs::path dir = scratch("numbers");
  Document doc;
  doc.table({{"parameter", "estimate", "relative std", "unit"},
             {{"m1", "1.2614", "0.0122 %", "kg"}, {"k", "-1.3e+06", "—", "N/m"}}});
  const std::string html = to_html(doc, dir.string());
  CHECK(html.find("<tr><th>parameter</th><th class=\"n\">estimate</th><th class=\"n\">relative std</th>"
                  "<th>unit</th></tr>") != std::string::npos);
  CHECK(html.find("<tr><td>k</td><td class=\"n\">-1.3e+06</td><td class=\"n\">—</td><td>N/m</td></tr>") !=
        std::string::npos);
}

TEST_CASE("the HTML embeds each plot as a data: URI, sized from the file", "[report][html]") {
  const fs::path dir = scratch("figures");
  write(dir / "plot.svg", "<svg viewBox=\"0 0 10 20\"/>");
  // A PNG's signature and IHDR chunk: 3 x 2 pixels.
  const std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\0\x03\0\0\0\x02", 24);
  write(dir / "plot.png", png);
  Document doc;
  doc.figure("plot.svg", "a plot");
  doc.figure("plot.png", "a bitmap");
  const std::string html = to_html(doc, dir.string());
  CHECK(html.find("<img alt=\"a plot\" width=\"10\" height=\"20\" "
                  "src=\"data:image/svg+xml;base64,PHN2ZyB2aWV3Qm94PSIwIDAgMTAgMjAiLz4=\">") != std::string::npos);
  CHECK(html.find("<img alt=\"a bitmap\" width=\"3\" height=\"2\" src=\"data:image/png;base64,iVBORw0KGgo") !=
        std::string::npos);
  // Self-contained: nothing names a place outside the file, and the policy allows no script and no request.
  CHECK(html.find("http:") == std::string::npos);
  CHECK(html.find("https:") == std::string::npos);
  CHECK(html.find("<link") == std::string::npos);
  CHECK(html.find("url(") == std::string::npos);
  CHECK(html.find("default-src 'none'; img-src data:") != std::string::npos);
  CHECK(to_html(doc, dir.string()) == html);  // deterministic
}

TEST_CASE("write_report writes report.md and report.html from one document", "[report]") {
  const fs::path dir = scratch("write");
  Document doc;
  doc.heading(1, "Title");
  doc.paragraph(Inline("file ") << code(hostile));
  write_report(dir.string(), doc, {});
  CHECK(slurp(dir / "report.md") == to_markdown(doc));
  CHECK(slurp(dir / "report.html") == to_html(doc, dir.string()));
  CHECK_FALSE(fs::exists(dir / "report.md.tmp"));
}
