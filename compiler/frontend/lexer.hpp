// Tokens of the .mdl language (docs/language.md).
//
// Newlines end statements, so the lexer reports them, except where a statement obviously goes on: inside
// ( ) or [ ], and after a `,`, `=` or an operator. That keeps the parser free of continuation rules.
#pragma once

#include <string>
#include <vector>

#include "ir/model_ir.hpp"

namespace mbgen::frontend {

enum class TokenKind { Name, Number, String, Punct, Newline, End };

struct Token {
  TokenKind kind = TokenKind::End;
  std::string text;  // name, number literal, string contents (without quotes), punctuation character
  ir::SourceLoc loc;
};

// Human-readable description for error messages, e.g. "name `foo`", "end of line".
std::string describe(const Token& t);

// Throws ModelError on a character that cannot start a token or an unterminated string.
std::vector<Token> tokenize(const std::string& text, const std::string& file_name);

}  // namespace mbgen::frontend
