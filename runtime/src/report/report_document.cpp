// The report document and its Markdown rendering (report.md).
#include "mbgen/report/report_document.hpp"

#include "mbgen/report/markdown.hpp"

#include <stdexcept>

namespace mbgen::report {

Inline& Inline::operator<<(std::string_view markup) {
  if (markup.empty()) return *this;
  if (!spans_.empty() && spans_.back().kind == Span::Kind::Markup) spans_.back().text += markup;  // one run
  else spans_.push_back({Span::Kind::Markup, std::string(markup)});
  return *this;
}

Inline& Inline::operator<<(Span span) {
  if (span.kind == Span::Kind::Markup) return *this << std::string_view(span.text);
  spans_.push_back(std::move(span));
  return *this;
}

Inline& Inline::operator<<(const Inline& more) {
  for (const Span& s : more.spans()) *this << s;
  return *this;
}

void Document::heading(int level, Inline text) {
  if (level < 1 || level > 4) throw std::logic_error("report heading level out of 1..4");
  blocks_.emplace_back(Heading{level, std::move(text)});
}

void Document::paragraph(Inline text) { blocks_.emplace_back(Paragraph{std::move(text)}); }

void Document::list(std::vector<Inline> items) {
  if (!items.empty()) blocks_.emplace_back(List{std::move(items)});  // nothing to list: no block
}

void Document::table(Table table) {
  for (const auto& row : table.rows)
    if (row.size() != table.header.size()) throw std::logic_error("report table row with the wrong number of cells");
  blocks_.emplace_back(std::move(table));
}

void Document::figure(std::string file, Inline alt) {
  for (const char c : file) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                    c == '-' || c == '.';
    if (!ok) throw std::logic_error("report figure file name is not a program-made stem: " + file);
  }
  blocks_.emplace_back(Figure{std::move(file), std::move(alt)});
}

namespace {

// In a table cell, `|` would end the cell: the program's own text gets it escaped too (user text already is).
std::string cell_markup(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '|' && (i == 0 || s[i - 1] != '\\')) out += '\\';
    out += s[i];
  }
  return out;
}

std::string markdown(const Inline& in, bool in_cell = false) {
  std::string out;
  for (const Span& s : in.spans()) {
    switch (s.kind) {
      case Span::Kind::Markup:
        out += in_cell ? cell_markup(s.text) : s.text;
        break;
      case Span::Kind::Text:
        out += markdown_text(s.text);
        break;
      case Span::Kind::Code:
        out += markdown_code(s.text);
        break;
    }
  }
  return out;
}

// `| a | b |`, an empty cell as `| |`.
std::string table_row(const std::vector<Inline>& cells) {
  std::string out = "|";
  for (const Inline& c : cells) {
    const std::string text = markdown(c, true);
    out += text.empty() ? " |" : " " + text + " |";
  }
  return out;
}

std::string markdown(const Block& block) {
  struct Render {
    std::string operator()(const Heading& h) const {
      return std::string(static_cast<std::size_t>(h.level), '#') + " " + markdown(h.text);
    }
    std::string operator()(const Paragraph& p) const { return markdown(p.text); }
    std::string operator()(const List& l) const {
      std::string out;
      for (std::size_t i = 0; i < l.items.size(); ++i) out += (i ? "\n- " : "- ") + markdown(l.items[i]);
      return out;
    }
    std::string operator()(const Table& t) const {
      std::string out = table_row(t.header) + "\n|";
      for (std::size_t i = 0; i < t.header.size(); ++i) out += "---|";
      for (const auto& row : t.rows) out += "\n" + table_row(row);
      return out;
    }
    std::string operator()(const Figure& f) const { return "![" + markdown(f.alt) + "](" + f.file + ")"; }
  };
  return std::visit(Render{}, block);
}

}  // namespace

std::string to_markdown(const Document& doc) {
  std::string out;
  for (const Block& b : doc.blocks()) {
    if (!out.empty()) out += "\n\n";
    out += markdown(b);
  }
  return out + "\n";
}

}  // namespace mbgen::report
