// The report document as one self-contained HTML file (report.html): styles inline, plots embedded as data: URIs.
#include "mbgen/report/report_document.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "text/string_format.hpp"

namespace mbgen::report {

namespace {

// Literal text: the five characters that HTML could read as markup escaped, control characters written as \xNN
// (as the Markdown shows them), so a user's string is only ever text.
std::string escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default:
        if (c < 0x20 || c == 0x7f) {
          out += detail::format("\\x%02X", c);
        } else {
          out += ch;
        }
    }
  }
  return out;
}

bool ascii_punctuation(char c) { return c > 0x20 && c < 0x7f && std::strchr("!\"#$%&'()*+,-./:;<=>?@[\\]^_`{|}~", c); }

std::size_t run_of(std::string_view s, std::size_t i, char c) {
  std::size_t n = 0;
  while (i + n < s.size() && s[i + n] == c) ++n;
  return n;
}

// Where the code span opened by `n` backticks at `from` closes (a run of exactly n), or npos.
std::size_t code_close(std::string_view s, std::size_t from, std::size_t n) {
  for (std::size_t j = from; j < s.size();) {
    const std::size_t m = run_of(s, j, '`');
    if (m == n) return j;
    j += m ? m : 1;
  }
  return std::string_view::npos;
}

// Where emphasis opened by `n` asterisks at `from` closes: the delimiter after a non-blank, or npos.
std::size_t emphasis_close(std::string_view s, std::size_t from, std::size_t n) {
  for (std::size_t j = from; j < s.size(); ++j) {
    if (s[j] == '\\') {
      ++j;
      continue;
    }
    if (s[j] == '`') {
      const std::size_t close = code_close(s, j + run_of(s, j, '`'), run_of(s, j, '`'));
      if (close != std::string_view::npos) j = close + run_of(s, close, '`') - 1;
      continue;
    }
    if (s[j] != '*' || s[j - 1] == ' ') continue;
    if (run_of(s, j, '*') == n) return j;
    j += run_of(s, j, '*') - 1;
  }
  return std::string_view::npos;
}

// The program's Markdown as HTML: the subset the report writers use (code spans, **strong**, *emphasis*, backslash
// escapes); everything else literal. `plain`: the text alone, without tags (for attributes).
std::string markup_html(std::string_view s, bool plain) {
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    const char c = s[i];
    if (c == '\\' && i + 1 < s.size() && ascii_punctuation(s[i + 1])) {
      out += escape(s.substr(i + 1, 1));
      i += 2;
    } else if (c == '`') {
      const std::size_t n = run_of(s, i, '`'), close = code_close(s, i + n, n);
      if (close == std::string_view::npos) {
        out += escape(s.substr(i, n));
        i += n;
        continue;
      }
      std::string_view body = s.substr(i + n, close - i - n);
      if (body.size() >= 2 && body.front() == ' ' && body.back() == ' ' && body.find_first_not_of(' ') != body.npos)
        body = body.substr(1, body.size() - 2);  // the padding that keeps a backtick from joining the fence
      out += plain ? escape(body) : "<code>" + escape(body) + "</code>";
      i = close + n;
    } else if (c == '*') {
      const std::size_t n = std::min<std::size_t>(run_of(s, i, '*'), 2);
      const std::size_t close = i + n < s.size() && s[i + n] != ' ' ? emphasis_close(s, i + n + 1, n) : s.npos;
      if (close == std::string_view::npos) {
        out += std::string(n, '*');
        i += n;
        continue;
      }
      const std::string inner = markup_html(s.substr(i + n, close - i - n), plain);
      const char* tag = n == 2 ? "strong" : "em";
      out += plain ? inner : std::string("<") + tag + ">" + inner + "</" + tag + ">";
      i = close + n;
    } else {
      const std::size_t next = s.find_first_of("\\`*", i + 1);
      const std::size_t end = next == std::string_view::npos ? s.size() : next;
      out += escape(s.substr(i, end - i));
      i = end;
    }
  }
  return out;
}

std::string html(const Inline& in, bool plain = false) {
  std::string out;
  for (const Span& s : in.spans()) {
    switch (s.kind) {
      case Span::Kind::Markup:
        out += markup_html(s.text, plain);
        break;
      case Span::Kind::Text:
        out += escape(s.text);
        break;
      case Span::Kind::Code:
        out += plain ? escape(s.text) : "<code>" + escape(s.text) + "</code>";
        break;
    }
  }
  return out;
}

// A cell that is one number (or a percentage); `blank`: also an empty cell or a dash (no value).
bool numeric(const Inline& cell, bool blank) {
  if (cell.empty()) return blank;
  if (cell.spans().size() != 1 || cell.spans()[0].kind != Span::Kind::Markup) return false;
  std::string s = cell.spans()[0].text;
  if (blank && (s == "—" || s == "n/a")) return true;
  if (s.size() > 2 && s.compare(s.size() - 2, 2, " %") == 0) s.resize(s.size() - 2);
  if (s.empty() || !std::strchr("0123456789+-.", s[0])) return false;
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

// The columns of numbers, right-aligned (header included) so that their digits line up: every cell a number or
// blank, at least one a number.
std::vector<bool> numeric_columns(const Table& t) {
  std::vector<bool> out(t.header.size(), false);
  for (std::size_t c = 0; c < t.header.size(); ++c) {
    bool all = !t.rows.empty(), any = false;
    for (const auto& row : t.rows) {
      all = all && numeric(row[c], true);
      any = any || numeric(row[c], false);
    }
    out[c] = all && any;
  }
  return out;
}

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t left = bytes.size() - i;
    std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (left > 1) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (left > 2) v |= static_cast<unsigned char>(bytes[i + 2]);
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += left > 1 ? digits[(v >> 6) & 63] : '=';
    out += left > 2 ? digits[v & 63] : '=';
  }
  return out;
}

std::optional<std::string> read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The size an image is drawn at: an SVG's viewBox (gnuplot's `dynamic` plots have no width and height), a PNG's
// header. Empty when not found: the browser then sizes it itself.
std::string size_attributes(const std::string& bytes, bool svg) {
  double w = 0, h = 0;
  if (svg) {
    const std::size_t tag = bytes.find("<svg");
    const std::size_t box = tag == std::string::npos ? tag : bytes.find("viewBox=\"", tag);
    const std::size_t tag_end = tag == std::string::npos ? tag : bytes.find('>', tag);
    double x = 0, y = 0;
    if (box == std::string::npos || box > tag_end ||
        std::sscanf(bytes.c_str() + box + 9, "%lf %lf %lf %lf", &x, &y, &w, &h) != 4)
      return "";
  } else {
    if (bytes.size() < 24 || bytes.compare(12, 4, "IHDR") != 0) return "";
    const auto be32 = [&](std::size_t at) {
      std::uint32_t v = 0;
      for (std::size_t k = 0; k < 4; ++k) v = v << 8 | static_cast<unsigned char>(bytes[at + k]);
      return v;
    };
    w = be32(16);
    h = be32(20);
  }
  if (!(w > 0 && h > 0 && w < 1e5 && h < 1e5)) return "";
  return detail::format(" width=\"%.0f\" height=\"%.0f\"", w, h);
}

std::string figure_html(const Figure& f, const std::string& dir) {
  const std::string alt = html(f.alt, true);
  const std::filesystem::path ext = std::filesystem::path(f.file).extension();
  const bool svg = ext == ".svg", png = ext == ".png";
  const std::optional<std::string> bytes =
      svg || png ? read_file(std::filesystem::path(dir) / f.file) : std::optional<std::string>();
  if (!bytes)
    return "<figure class=\"missing\"><figcaption>" + alt + ": <code>" + escape(f.file) +
           "</code> was not drawn (see the note at the end)</figcaption></figure>";
  return "<figure><img alt=\"" + alt + "\"" + size_attributes(*bytes, svg) + " src=\"data:image/" +
         (svg ? "svg+xml" : "png") + ";base64," + base64(*bytes) + "\"></figure>";
}

std::string row_html(const std::vector<Inline>& cells, const std::vector<bool>& numbers, const char* tag) {
  std::string out = "<tr>";
  for (std::size_t c = 0; c < cells.size(); ++c)
    out += std::string("<") + tag + (numbers[c] ? " class=\"n\">" : ">") + html(cells[c]) + "</" + tag + ">";
  return out + "</tr>";
}

std::string block_html(const Block& block, const std::string& dir) {
  struct Render {
    const std::string& dir;
    std::string operator()(const Heading& h) const {
      const std::string tag = "h" + std::to_string(h.level);
      return "<" + tag + ">" + html(h.text) + "</" + tag + ">";
    }
    std::string operator()(const Paragraph& p) const { return "<p>" + html(p.text) + "</p>"; }
    std::string operator()(const List& l) const {
      std::string out = "<ul>";
      for (const Inline& item : l.items) out += "\n<li>" + html(item) + "</li>";
      return out + "\n</ul>";
    }
    std::string operator()(const Table& t) const {
      const std::vector<bool> numbers = numeric_columns(t);
      std::string out =
          "<div class=\"table\"><table>\n<thead>" + row_html(t.header, numbers, "th") + "</thead>\n<tbody>";
      for (const auto& row : t.rows) out += "\n" + row_html(row, numbers, "td");
      return out + "\n</tbody></table></div>";
    }
    std::string operator()(const Figure& f) const { return figure_html(f, dir); }
  };
  return std::visit(Render{dir}, block);
}

// Readable on a screen and on paper: wide tables scroll within their box, names in cells are not broken, numbers
// in tabular figures.
const char* const style = R"(body{margin:0;background:#fff;color:#1b1b1b;
font:15px/1.5 system-ui,-apple-system,"Segoe UI",Roboto,"DejaVu Sans",sans-serif}
main{max-width:980px;margin:0 auto;padding:1.2em 1.5em 3em}
h1{font-size:1.55em;margin:.4em 0 .6em;padding-bottom:.25em;border-bottom:2px solid #d0d7de}
h2{font-size:1.3em;margin:1.8em 0 .6em;padding-bottom:.2em;border-bottom:1px solid #e4e8ec}
h3{font-size:1.12em;margin:1.5em 0 .5em}
h4{font-size:1em;margin:1.3em 0 .4em}
p,ul{margin:.6em 0}
li{margin:.2em 0}
code{font-family:ui-monospace,"DejaVu Sans Mono",Menlo,Consolas,monospace;font-size:.88em;background:#f2f4f6;
padding:.05em .3em;border-radius:3px;overflow-wrap:anywhere}
td code,th code{white-space:nowrap;overflow-wrap:normal}
.table{overflow-x:auto;margin:.9em 0}
table{border-collapse:collapse;font-size:.9em}
th,td{border:1px solid #d0d7de;padding:.3em .65em;text-align:left;vertical-align:top}
th{background:#eef2f6;font-weight:600}
tbody tr:nth-child(even){background:#f8fafc}
td.n,th.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
figure{margin:1em 0}
img{display:block;max-width:100%;height:auto;border:1px solid #e4e8ec}
figure.missing figcaption{padding:.8em;border:1px dashed #b0b7be;color:#555}
@media print{main{max-width:none}.table{overflow:visible}figure,tr{break-inside:avoid}})";

}  // namespace

std::string to_html(const Document& doc, const std::string& dir) {
  std::string title = "mbgen report";
  for (const Block& b : doc.blocks())
    if (const auto* h = std::get_if<Heading>(&b); h && h->level == 1) {
      title = html(h->text, true);
      break;
    }
  std::string out =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      // Nothing runs and nothing is fetched, whatever a string might have smuggled in: images from data: only.
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
      "style-src 'unsafe-inline'\">\n<title>" +
      title + "</title>\n<style>\n" + style + "\n</style>\n</head>\n<body>\n<main>\n";
  for (const Block& b : doc.blocks()) out += block_html(b, dir) + "\n";
  return out + "</main>\n</body>\n</html>\n";
}

}  // namespace mbgen::report
