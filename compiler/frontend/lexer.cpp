#include "frontend/lexer.hpp"

#include <cctype>

#include "frontend/diagnostics.hpp"

namespace mbgen::frontend {

std::string describe(const Token& t) {
  switch (t.kind) {
    case TokenKind::Name: return "`" + t.text + "`";
    case TokenKind::Number: return "number `" + t.text + "`";
    case TokenKind::String: return "string \"" + t.text + "\"";
    case TokenKind::Punct: return "`" + t.text + "`";
    case TokenKind::Newline: return "end of line";
    case TokenKind::End: return "end of file";
  }
  return "?";
}

namespace {

class Lexer {
 public:
  Lexer(const std::string& text, const std::string& file) : text_(text), file_(file) {
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;  // a UTF-8 byte order mark, as some editors write
  }

  std::vector<Token> run() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        newline();
      } else if (c == ' ' || c == '\t' || c == '\r') {
        advance();
      } else if (c == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') advance();
      } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
        name();
      } else if (std::isdigit(static_cast<unsigned char>(c)) ||
                 (c == '.' && pos_ + 1 < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_ + 1])))) {
        number();
      } else if (c == '"') {
        string();
      } else if (std::string("(){}[],;=+-*/^").find(c) != std::string::npos) {
        punct(c);
      } else {
        const unsigned char u = static_cast<unsigned char>(c);
        const std::string shown = u >= 32 && u < 127 ? std::string("`") + c + "`" : "byte " + std::to_string(u);
        throw ModelError(file_, here(), "unexpected character " + shown);
      }
    }
    end_line(here());
    push({TokenKind::End, "", here()});
    return std::move(tokens_);
  }

 private:
  ir::SourceLoc here() const { return {line_, column_}; }

  void advance() {
    ++pos_;
    ++column_;
  }

  void push(Token t) { tokens_.push_back(std::move(t)); }

  // A newline ends a statement unless brackets are open or the last token expects more.
  void newline() {
    const ir::SourceLoc loc = here();
    ++pos_;
    ++line_;
    column_ = 1;
    end_line(loc);
  }

  void end_line(ir::SourceLoc loc) {
    if (depth_ > 0 || tokens_.empty()) return;
    const Token& last = tokens_.back();
    if (last.kind == TokenKind::Newline) return;
    if (last.kind == TokenKind::Punct && std::string(",=+-*/^{").find(last.text) != std::string::npos) return;
    push({TokenKind::Newline, "", loc});
  }

  void name() {
    const ir::SourceLoc loc = here();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_'))
      advance();
    push({TokenKind::Name, text_.substr(start, pos_ - start), loc});
  }

  void digits() {
    while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) advance();
  }

  void number() {
    const ir::SourceLoc loc = here();
    const std::size_t start = pos_;
    digits();
    if (pos_ < text_.size() && text_[pos_] == '.') {
      advance();
      digits();
    }
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t look = pos_ + 1;
      if (look < text_.size() && (text_[look] == '+' || text_[look] == '-')) ++look;
      if (look < text_.size() && std::isdigit(static_cast<unsigned char>(text_[look]))) {
        while (pos_ < look) advance();
        digits();
      }
    }
    if (pos_ < text_.size() && (std::isalpha(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_'))
      throw ModelError(file_, loc, "malformed number `" + text_.substr(start, pos_ - start + 1) +
                                          "`: a number must not run into a name");
    push({TokenKind::Number, text_.substr(start, pos_ - start), loc});
  }

  void string() {
    const ir::SourceLoc loc = here();
    advance();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '"' && text_[pos_] != '\n') advance();
    if (pos_ >= text_.size() || text_[pos_] != '"')
      throw ModelError(file_, loc, "unterminated string: expected a closing `\"` on the same line");
    push({TokenKind::String, text_.substr(start, pos_ - start), loc});
    advance();
  }

  void punct(char c) {
    if (c == '(' || c == '[') ++depth_;
    if ((c == ')' || c == ']') && depth_ > 0) --depth_;
    push({TokenKind::Punct, std::string(1, c), here()});
    advance();
  }

  const std::string& text_;
  const std::string& file_;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1, depth_ = 0;
  std::vector<Token> tokens_;
};

}  // namespace

std::vector<Token> tokenize(const std::string& text, const std::string& file_name) {
  return Lexer(text, file_name).run();
}

}  // namespace mbgen::frontend
