#include "diagnosis/text_patch.hpp"

#include <algorithm>
#include <stdexcept>

namespace mbgen::diagnosis {

using frontend::TokenKind;

TextPatch::TextPatch(std::string original, const std::string& file_name)
    : original_(std::move(original)), tokens_(frontend::tokenize(original_, file_name)) {
  line_starts_.push_back(0);
  for (std::size_t i = 0; i < original_.size(); ++i)
    if (original_[i] == '\n') line_starts_.push_back(i + 1);
}

std::size_t TextPatch::offset(ir::SourceLoc loc) const {
  if (loc.line < 1 || static_cast<std::size_t>(loc.line) > line_starts_.size() || loc.column < 1)
    throw std::logic_error("text patch: location " + std::to_string(loc.line) + ":" + std::to_string(loc.column) +
                           " is not in the model text (was the model parsed from it?)");
  return line_starts_[loc.line - 1] + loc.column - 1;
}

std::size_t TextPatch::token_at(ir::SourceLoc loc, const std::string& expected) const {
  for (std::size_t i = 0; i < tokens_.size(); ++i)
    if (tokens_[i].loc.line == loc.line && tokens_[i].loc.column == loc.column) {
      if (tokens_[i].kind != TokenKind::Name || tokens_[i].text != expected) break;
      return i;
    }
  throw std::logic_error("text patch: expected the name `" + expected + "` at " + std::to_string(loc.line) + ":" +
                         std::to_string(loc.column) + " of the model text");
}

std::size_t TextPatch::token_end(std::size_t i) const {
  const frontend::Token& t = tokens_[i];
  return offset(t.loc) + t.text.size() + (t.kind == TokenKind::String ? 2 : 0);
}

TextPatch::Range TextPatch::statement(ir::SourceLoc name_loc) const {
  const std::size_t name = [&] {
    for (std::size_t i = 0; i < tokens_.size(); ++i)
      if (tokens_[i].loc.line == name_loc.line && tokens_[i].loc.column == name_loc.column) return i;
    throw std::logic_error("text patch: no token at " + std::to_string(name_loc.line) + ":" +
                           std::to_string(name_loc.column));
  }();
  if (name == 0) throw std::logic_error("text patch: a statement name with no keyword before it");
  // Every statement reads `KEYWORD NAME ...`; a block's braces hold newlines that do not end it.
  int depth = 0;
  std::size_t j = name;
  for (; tokens_[j].kind != TokenKind::End; ++j) {
    const frontend::Token& t = tokens_[j];
    const bool punct = t.kind == TokenKind::Punct;
    if (depth == 0 && (t.kind == TokenKind::Newline || (punct && t.text == ";"))) break;
    if (punct && t.text == "{") ++depth;
    if (punct && t.text == "}") --depth;
  }
  return {name - 1, j - 1};
}

std::size_t TextPatch::line_end(std::size_t at) const {
  const std::size_t nl = original_.find('\n', at);
  return nl == std::string::npos ? original_.size() : nl;
}

bool TextPatch::owns_its_lines(const Range& r) const {
  const std::size_t begin = offset(tokens_[r.first].loc);
  const std::size_t line_begin = line_starts_[tokens_[r.first].loc.line - 1];
  for (std::size_t i = line_begin; i < begin; ++i)
    if (original_[i] != ' ' && original_[i] != '\t') return false;
  const std::size_t end = token_end(r.last);
  for (std::size_t i = end; i < line_end(end); ++i) {
    if (original_[i] == '#') return true;
    if (original_[i] != ' ' && original_[i] != '\t' && original_[i] != '\r') return false;
  }
  return true;
}

void TextPatch::edit(std::size_t begin, std::size_t end, std::string text) {
  edits_.push_back({begin, end, std::move(text), edits_.size()});
}

void TextPatch::rename(ir::SourceLoc loc, const std::string& expected, const std::string& replacement) {
  const std::size_t i = token_at(loc, expected);
  edit(offset(tokens_[i].loc), token_end(i), replacement);
}

void TextPatch::insert_after(ir::SourceLoc loc, const std::string& expected, const std::string& text) {
  const std::size_t end = token_end(token_at(loc, expected));
  edit(end, end, text);
}

void TextPatch::replace_statement(ir::SourceLoc name_loc, const std::string& note, const std::string& replacement) {
  const Range r = statement(name_loc);
  if (!owns_its_lines(r)) {
    // It shares a line with other statements: put the replacement in its place, on lines of its own.
    edit(offset(tokens_[r.first].loc), token_end(r.last), replacement.empty() ? "" : "\n" + replacement);
    appended_ += "# " + note + "\n";
    return;
  }
  const int first_line = tokens_[r.first].loc.line;
  const int last_line = tokens_[r.last].loc.line;
  const std::size_t first_begin = line_starts_[first_line - 1];
  edit(first_begin, first_begin, "# mbgen diagnose: " + note + "\n");
  for (int line = first_line; line <= last_line; ++line) edit(line_starts_[line - 1], line_starts_[line - 1], "# ");
  const std::size_t after = line_end(line_starts_[last_line - 1]);
  if (replacement.empty()) return;
  if (after == original_.size()) edit(after, after, "\n" + replacement);
  else edit(after + 1, after + 1, replacement);
}

void TextPatch::change_role(ir::SourceLoc name_loc, const std::string& from, const std::string& to,
                            const std::string& note) {
  const Range r = statement(name_loc);
  // The role follows a complete value (a number, a name, `)`) or the unit string; a parameter *named* like the
  // role word inside the value would follow an operator instead.
  for (std::size_t i = r.first + 3; i <= r.last; ++i) {
    const frontend::Token& t = tokens_[i];
    const frontend::Token& before = tokens_[i - 1];
    const bool after_value = before.kind == TokenKind::Number || before.kind == TokenKind::Name ||
                             before.kind == TokenKind::String || (before.kind == TokenKind::Punct && before.text == ")");
    if (t.kind == TokenKind::Name && t.text == from && after_value) {
      edit(offset(t.loc), token_end(i), to);
      if (owns_its_lines(r)) {
        const std::size_t end = line_end(token_end(r.last));
        edit(end, end, "  # mbgen diagnose: " + note);
      } else {
        appended_ += "# " + note + "\n";
      }
      return;
    }
  }
  throw std::logic_error("text patch: no role `" + from + "` in the declaration at line " +
                         std::to_string(name_loc.line));
}

void TextPatch::replace_number(ir::SourceLoc name_loc, const std::string& literal) {
  const Range r = statement(name_loc);
  const std::size_t first = r.first + 3;  // `param NAME = ` then the value
  const bool sign = first < r.last && tokens_[first].kind == TokenKind::Punct && tokens_[first].text == "-";
  const std::size_t last = sign ? first + 1 : first;
  // A number alone: what follows (unit, role, bounds) must not continue an expression.
  const bool continued = last < r.last && tokens_[last + 1].kind == TokenKind::Punct &&
                         std::string("+-*/^").find(tokens_[last + 1].text) != std::string::npos;
  if (last > r.last || tokens_[last].kind != TokenKind::Number || continued)
    throw std::logic_error("text patch: the declaration at line " + std::to_string(name_loc.line) +
                           " is not `param NAME = NUMBER`");
  edit(offset(tokens_[first].loc), token_end(last), literal);
}

void TextPatch::append(const std::string& text) { appended_ += text; }

void TextPatch::rewrite_statement(ir::SourceLoc name_loc, const std::string& replacement) {
  const Range r = statement(name_loc);
  edit(offset(tokens_[r.first].loc), token_end(r.last), replacement);
}

std::string TextPatch::result(const std::string& title) const {
  return text() + "\n# --- mbgen diagnose: " + title + " ---\n" + appended_;
}

std::string TextPatch::text() const {
  std::vector<Edit> edits = edits_;
  std::sort(edits.begin(), edits.end(),
            [](const Edit& a, const Edit& b) { return a.begin != b.begin ? a.begin < b.begin : a.order < b.order; });
  std::string out;
  std::size_t pos = 0;
  for (const Edit& e : edits) {
    if (e.begin < pos) throw std::logic_error("text patch: overlapping edits of the model text");
    out.append(original_, pos, e.begin - pos);
    out += e.text;
    pos = e.end;
  }
  out.append(original_, pos, std::string::npos);
  if (!out.empty() && out.back() != '\n') out += '\n';
  return out;
}

}  // namespace mbgen::diagnosis
