// A report as a small document (headings, paragraphs, lists, tables, figures of inline text), written once by each
// report writer (fit, diagnose, monitor, modal, sensitivity) and rendered twice: to Markdown (report.md) and to one
// self-contained HTML file (report.html, its plots embedded). Each piece of inline text says whether it is the
// program's own Markdown or a user's string, so that each rendering escapes what it must.
#pragma once

#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

namespace mbgen::report {

struct Span {
  enum class Kind {
    Markup,  // the program's own text, written to the Markdown as it is; in the HTML, `code`, **strong**,
             // *emphasis* and backslash escapes show as a Markdown renderer shows them. Never a user's string.
    Text,    // a user's string (a file name, a channel name, a unit): literal text in both renderings
    Code,    // a user's string shown as code
  };
  Kind kind = Kind::Markup;
  std::string text;
};

// A user's string as literal text, and as code.
inline Span text(std::string s) { return {Span::Kind::Text, std::move(s)}; }
inline Span code(std::string s) { return {Span::Kind::Code, std::move(s)}; }

// A run of spans. Strings are the program's Markdown (Span::Kind::Markup); numbers are written as an ostream
// writes them by default (6 significant digits).
class Inline {
 public:
  Inline() = default;
  Inline(std::string_view markup) { *this << markup; }  // NOLINT: implicit, so that "text" is an Inline
  Inline(const char* markup) : Inline(std::string_view(markup)) {}
  Inline(const std::string& markup) : Inline(std::string_view(markup)) {}
  Inline(Span span) { *this << std::move(span); }

  Inline& operator<<(std::string_view markup);
  Inline& operator<<(const char* markup) { return *this << std::string_view(markup); }
  Inline& operator<<(const std::string& markup) { return *this << std::string_view(markup); }
  Inline& operator<<(Span span);
  Inline& operator<<(const Inline& more);
  template <typename T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, char> &&
                                             !std::is_same_v<T, bool>, int> = 0>
  Inline& operator<<(T number) {
    std::ostringstream s;
    s << number;
    return *this << s.str();
  }

  const std::vector<Span>& spans() const { return spans_; }
  bool empty() const { return spans_.empty(); }

 private:
  std::vector<Span> spans_;
};

struct Heading {
  int level = 1;  // 1 to 4
  Inline text;
};
struct Paragraph {
  Inline text;
};
struct List {
  std::vector<Inline> items;
};
struct Table {
  std::vector<Inline> header;
  std::vector<std::vector<Inline>> rows;  // as many cells as the header
};
// An image file in the report directory, named by the program (letters, digits, `_`, `-`, `.` only).
struct Figure {
  std::string file;
  Inline alt;
};
using Block = std::variant<Heading, Paragraph, List, Table, Figure>;

class Document {
 public:
  void heading(int level, Inline text);
  void paragraph(Inline text);
  void list(std::vector<Inline> items);  // no items: no block
  void table(Table table);
  // Throws std::logic_error for a file name other than the program's own (see Figure).
  void figure(std::string file, Inline alt);

  const std::vector<Block>& blocks() const { return blocks_; }

 private:
  std::vector<Block> blocks_;
};

// The Markdown: blocks separated by a blank line, the file ending in one newline.
std::string to_markdown(const Document& doc);

// One HTML file that needs nothing else: the styles inline, each figure read from `dir` and embedded as a data:
// URI (an image cannot run scripts nor load anything), every string escaped, a Content-Security-Policy that allows
// no script and no request. A figure whose file is missing (gnuplot was not there) is a note in its place. The
// same document and files give the same bytes.
std::string to_html(const Document& doc, const std::string& dir);

// Draws the plots (each STEM.gp in `dir`, see gnuplot.hpp), adds the note when they could not be drawn, and writes
// DIR/report.md and DIR/report.html, each whole or not at all. Throws FitError when it cannot write them.
void write_report(const std::string& dir, Document doc, const std::vector<std::string>& plot_stems);

}  // namespace mbgen::report
