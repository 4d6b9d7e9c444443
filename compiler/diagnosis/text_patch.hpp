// Small, commented edits of a model's original text: how an extended model is shown to its author.
//
// Edits are located by the source locations the parser stored in the IR (the text is tokenized again with the
// front end's lexer to find where statements begin and end). Replaced statements stay in the text, commented
// out, below a note that says what changed; new declarations go at the end, after a
// `# --- mbgen diagnose: <id>: <description> ---` line.
#pragma once

#include <string>
#include <vector>

#include "frontend/lexer.hpp"
#include "ir/model_ir.hpp"

namespace mbgen::diagnosis {

class TextPatch {
 public:
  // `file_name` is used in lexer errors only.
  TextPatch(std::string original, const std::string& file_name);

  // Replaces the name token at `loc`, which must read `expected` (e.g. a parameter reference).
  void rename(ir::SourceLoc loc, const std::string& expected, const std::string& replacement);

  // Inserts `text` right after the name token at `loc`, which must read `expected`.
  void insert_after(ir::SourceLoc loc, const std::string& expected, const std::string& text);

  // Replaces the statement whose name token (the word after its keyword) is at `name_loc` by `replacement`
  // (complete statements ending in a newline; empty to remove it). When the statement has its lines to itself
  // they are kept, commented out, below `# mbgen diagnose: NOTE`; otherwise the note goes to the end section.
  void replace_statement(ir::SourceLoc name_loc, const std::string& note, const std::string& replacement);

  // Changes the role word (`fixed` -> `estimate`) of the parameter declared with its name at `name_loc`, noting
  // the change in a comment on the same line (or in the end section if the line goes on).
  void change_role(ir::SourceLoc name_loc, const std::string& from, const std::string& to, const std::string& note);

  // Replaces the number a parameter is declared with (`param NAME = NUMBER ...`, a sign included) by `literal`,
  // in place: the rest of the declaration (unit, role, bounds, comment) stays as written.
  void replace_number(ir::SourceLoc name_loc, const std::string& literal);

  // Replaces the tokens of the statement whose name token is at `name_loc` by `replacement` (one statement, no
  // newline), in place: the lines keep their numbers and a trailing comment stays.
  void rewrite_statement(ir::SourceLoc name_loc, const std::string& replacement);

  // Text for the end section (complete statements or comment lines, each ending in a newline).
  void append(const std::string& text);

  // The edited text, then the end section under `# --- mbgen diagnose: TITLE ---`.
  std::string result(const std::string& title) const;
  // The edited text alone (ending in a newline).
  std::string text() const;

 private:
  struct Edit {
    std::size_t begin, end;  // replaced byte range of the original (begin == end: an insertion)
    std::string text;
    std::size_t order;       // edits at one offset apply in the order they were made
  };
  struct Range {
    std::size_t first, last;  // token indices of a statement, keyword to last token
  };

  std::size_t offset(ir::SourceLoc loc) const;
  std::size_t token_at(ir::SourceLoc loc, const std::string& expected) const;
  std::size_t token_end(std::size_t index) const;
  Range statement(ir::SourceLoc name_loc) const;
  bool owns_its_lines(const Range& r) const;  // nothing but blanks and a comment share its lines
  std::size_t line_end(std::size_t offset) const;  // offset of the '\n' ending that line (or the text size)
  void edit(std::size_t begin, std::size_t end, std::string text);

  std::string original_;
  std::vector<frontend::Token> tokens_;
  std::vector<std::size_t> line_starts_;
  std::vector<Edit> edits_;
  std::string appended_;
};

}  // namespace mbgen::diagnosis
