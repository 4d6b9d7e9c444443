// Internal helpers shared by the data readers: line reading with line numbers, field splitting, strict
// number parsing, and the `# set` / `# hold` configuration lines.
#pragma once

#include <cstddef>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mbgen/data/data_settings.hpp"

namespace mbgen::data_detail {

std::string_view trim(std::string_view s);

// Reads lines, counting them from 1 and dropping a trailing '\r' (files written on Windows). A line longer than
// kMaxLineBytes is a DataError naming `file` and the line: `--data /dev/zero` (no newline ever) grew one line until
// the memory ran out.
constexpr std::size_t kMaxLineBytes = std::size_t(16) << 20;
class LineReader {
 public:
  LineReader(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}
  bool next(std::string& line);
  // Up to `n` bytes as they are (a binary block between lines), counting the newlines among them as lines so that
  // the lines after it keep their numbers. Returns how many bytes there were.
  std::size_t read_block(char* out, std::size_t n);
  int line_number() const { return line_; }

 private:
  std::istream& in_;
  std::string file_;
  int line_ = 0;
};

// Splits at commas; fields are trimmed of blanks. Quoting is not supported.
std::vector<std::string_view> split_fields(std::string_view line);

// The whole of `text` as a decimal number (a leading '+' allowed; with `fortran_exponent` also 'D' as the
// exponent letter). Returns nullopt when it is not one; the value may be non-finite ("nan", "inf").
std::optional<double> parse_number(std::string_view text, bool fortran_exponent = false);

// Whitespace-separated tokens with their 1-based columns. Fortran writes fixed-width fields that may run
// together ("1.5E+00-2.5E+00"): a sign right after a digit or '.' starts a new number.
std::vector<std::pair<std::string_view, int>> fortran_number_tokens(std::string_view line);

// Measured values larger than this in magnitude are rejected: their squares (spectra, sums of squares in a fit)
// would overflow a double and give NaN results. No physical measurement comes near it.
constexpr double kMaxDataMagnitude = 1e150;
// The message for such a value, e.g. "'1e300' is too large (...)".
std::string too_large_message(std::string_view text);

// True for a C-like identifier: a letter or '_' followed by letters, digits or '_'.
bool is_identifier(std::string_view s);

// Configuration collected from lines such as `# set NAME=VALUE` and `# hold=none`.
struct DataConfig {
  SetMap set;
  std::optional<HoldMode> hold;
  int hold_line = 0;  // where `hold=` was given, for messages
};

// `body` is a comment line's text after '#'. Returns false when it is a free comment; records a `set` or
// `hold=` line in `config`, throwing DataError at (file, line) when its syntax is bad or it repeats a name.
bool parse_config_comment(std::string_view body, const std::string& file, int line, DataConfig& config);

// The shortest decimal text that reads back as the same double.
std::string format_double(double v);

}  // namespace mbgen::data_detail
