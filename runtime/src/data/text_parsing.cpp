#include "text_parsing.hpp"

#include <charconv>
#include <limits>
#include <cmath>

#include "mbgen/data/data_error.hpp"

namespace mbgen::data_detail {

std::string_view trim(std::string_view s) {
  const char* blanks = " \t\r\n\v\f";
  const auto b = s.find_first_not_of(blanks);
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(blanks);
  return s.substr(b, e - b + 1);
}

bool LineReader::next(std::string& line) {
  // istream::getline into a buffer stops when the buffer is full (failbit, the rest of the line still unread), where
  // std::getline would grow the string without end. A line takes one call unless it is longer than the buffer.
  // Counts come from gcount(), not strlen: a line may hold NUL bytes.
  char chunk[1 << 16];
  line.clear();
  bool any = false;
  while (true) {
    in_.getline(chunk, sizeof chunk);
    const auto got = static_cast<std::size_t>(in_.gcount());
    if (in_.eof()) {  // the last line, without a newline, or nothing more
      line.append(chunk, got);
      any = any || got > 0;
      break;
    }
    if (!in_.fail()) {  // a newline ended the line (counted in gcount, not stored)
      line.append(chunk, got - 1);
      any = true;
      break;
    }
    if (in_.bad()) return false;
    line.append(chunk, got);  // the buffer was full: the line goes on
    any = true;
    in_.clear();
    if (line.size() > kMaxLineBytes) break;
  }
  if (line.size() > kMaxLineBytes)
    throw DataError(file_, line_ + 1, 0, "line longer than " + std::to_string(kMaxLineBytes >> 20) + " MiB");
  if (!any) return false;
  ++line_;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

std::size_t LineReader::read_block(char* out, std::size_t n) {
  in_.read(out, static_cast<std::streamsize>(n));
  const auto got = static_cast<std::size_t>(in_.gcount());
  for (std::size_t i = 0; i < got; ++i)
    if (out[i] == '\n') ++line_;
  return got;
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos
                                                                            : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

std::optional<double> parse_number(std::string_view text, bool fortran_exponent) {
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    if (!text.empty() && (text.front() == '+' || text.front() == '-')) return std::nullopt;
  }
  if (text.empty()) return std::nullopt;
  std::string buffer;
  if (fortran_exponent && text.find_first_of("Dd") != std::string_view::npos) {
    buffer.assign(text);
    for (char& c : buffer)
      if (c == 'D' || c == 'd') c = 'E';
    text = buffer;
  }
  double value = 0;
  // from_chars is locale independent, unlike strtod: a German locale must not turn "0.5" into an error.
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (end != text.data() + text.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {
    // Beyond a double's range. A magnitude under the smallest double is zero, as every reader rounds it (1e-400
    // was "not a number"); one over the largest is returned as the largest, which the readers reject as too large.
    const std::size_t e = text.find_first_of("eE");
    const std::string_view mantissa = text.substr(0, e);
    const bool tiny = e != std::string_view::npos ? e + 1 < text.size() && text[e + 1] == '-'
                                                  : mantissa.find_first_not_of("+-0") == mantissa.find('.');
    const double magnitude = tiny ? 0.0 : std::numeric_limits<double>::max();
    return text.front() == '-' ? -magnitude : magnitude;
  }
  if (ec != std::errc()) return std::nullopt;
  return value;
}

std::string too_large_message(std::string_view text) {
  return "'" + std::string(text) + "' is too large: magnitudes above 1e150 are rejected (their squares overflow)";
}

bool is_identifier(std::string_view s) {
  if (s.empty()) return false;
  auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (!letter(s.front())) return false;
  for (char c : s)
    if (!letter(c) && !(c >= '0' && c <= '9')) return false;
  return true;
}

bool parse_config_comment(std::string_view body, const std::string& file, int line, DataConfig& config) {
  const std::string_view text = trim(body);
  // A configuration line starts with the word `set` or with `hold`; anything else is a free comment.
  const bool is_set = text == "set" || text.substr(0, 4) == "set " || text.substr(0, 4) == "set\t";
  const bool is_hold = text.substr(0, 4) == "hold" &&
                       (text.size() == 4 || text[4] == '=' || text[4] == ' ' || text[4] == '\t');
  if (!is_set && !is_hold) return false;
  if (is_set) {
    const std::string_view assignment = trim(text.substr(3));
    const auto eq = assignment.find('=');
    const std::string_view name = trim(assignment.substr(0, eq));
    if (eq == std::string_view::npos || !is_identifier(name))
      throw DataError(file, line, 0,
                      "bad '# set' line '" + std::string(text) +
                          "': expected '# set NAME=VALUE' with NAME a parameter name");
    const std::string_view value_text = trim(assignment.substr(eq + 1));
    const auto value = parse_number(value_text);
    if (!value || !std::isfinite(*value))
      throw DataError(file, line, 0,
                      "bad '# set' line: value '" + std::string(value_text) + "' of '" + std::string(name) +
                          "' is not a finite decimal number");
    if (config.set.count(std::string(name)))
      throw DataError(file, line, 0, "parameter '" + std::string(name) + "' is set twice");
    config.set[std::string(name)] = SetValue{std::string(value_text), *value, line};
    return true;
  }
  const auto eq = text.find('=');
  const std::string_view key = trim(text.substr(0, eq));
  const std::string_view mode = eq == std::string_view::npos ? std::string_view() : trim(text.substr(eq + 1));
  if (key != "hold" || (mode != "none" && mode != "zoh"))
    throw DataError(file, line, 0,
                    "bad '# hold' line '" + std::string(text) + "': expected '# hold=none' or '# hold=zoh'");
  if (config.hold)
    throw DataError(file, line, 0,
                    "hold mode given twice (first on line " + std::to_string(config.hold_line) + ")");
  config.hold = mode == "none" ? HoldMode::None : HoldMode::ZeroOrder;
  config.hold_line = line;
  return true;
}

std::string format_double(double v) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  (void)ec;  // 64 characters always suffice for a double
  return std::string(buffer, end);
}

std::vector<std::pair<std::string_view, int>> fortran_number_tokens(std::string_view line) {
  std::vector<std::pair<std::string_view, int>> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i >= line.size()) break;
    std::size_t start = i;
    ++i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') {
      const char prev = line[i - 1];
      if ((line[i] == '-' || line[i] == '+') && ((prev >= '0' && prev <= '9') || prev == '.')) {
        tokens.emplace_back(line.substr(start, i - start), static_cast<int>(start) + 1);
        start = i;
      }
      ++i;
    }
    tokens.emplace_back(line.substr(start, i - start), static_cast<int>(start) + 1);
  }
  return tokens;
}

}  // namespace mbgen::data_detail
