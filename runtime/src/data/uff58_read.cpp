// Reading UFF datasets 58 (ASCII) and 58b (binary header line, 11 ASCII header lines, binary body).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>

#include "mbgen/data/data_error.hpp"
#include "mbgen/data/uff.hpp"
#include "text_parsing.hpp"

namespace mbgen {

using namespace data_detail;

namespace {

// Walks the file line by line from the stream (never holding the whole file: `--data x.uff` naming /dev/zero, or a
// stray huge file, grew one string until the memory ran out); a line is at most kMaxLineBytes (LineReader). Binary
// bodies are taken by byte count. A line returned stays valid until the next call.
class Cursor {
 public:
  Cursor(std::istream& in, const std::string& file) : reader_(in, file) {}
  bool next_line(std::string_view& line) {
    if (!reader_.next(buffer_)) return false;
    line = buffer_;
    return true;
  }
  // Up to n bytes of a binary block; line numbers after it stay as an editor would show them.
  std::size_t take(char* out, std::size_t n) { return reader_.read_block(out, n); }
  int line() const { return reader_.line_number(); }

 private:
  LineReader reader_;
  std::string buffer_;
};

bool is_delimiter(std::string_view line) { return trim(line) == "-1"; }

std::string shown(std::string_view text) {
  std::string s(trim(text).substr(0, 40));
  return "'" + s + "'";
}

// A fixed-width field (Fortran format), trimmed; empty when the line is shorter.
std::string_view field(std::string_view line, std::size_t start, std::size_t width) {
  if (start >= line.size()) return {};
  return trim(line.substr(start, width));
}

struct LineContext {
  const std::string& file;
  int line;
  const char* record;  // e.g. "record 6"
};

long long parse_integer(std::string_view text, const LineContext& at, int column, const char* what) {
  const auto v = parse_number(text, true);
  if (!v || *v != std::floor(*v) || std::abs(*v) > 9e15)
    throw DataError(at.file, at.line, column,
                    std::string("UFF 58 ") + at.record + ": " + what + " " + shown(text) + " is not an integer");
  return static_cast<long long>(*v);
}

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// Values per point: abscissa (when uneven) plus one (real) or two (complex) ordinate values.
Eigen::Index values_per_point(const Uff58Record& r) { return (r.even_spacing ? 0 : 1) + (r.is_complex() ? 2 : 1); }

void fill_points(Uff58Record& r, const std::vector<double>& v) {
  const Eigen::Index per = values_per_point(r);
  r.x.resize(r.points);
  r.y.resize(r.points);
  for (Eigen::Index k = 0; k < r.points; ++k) {
    const double* p = v.data() + k * per;
    if (r.even_spacing) {
      r.x[k] = r.abscissa_min + static_cast<double>(k) * r.abscissa_increment;
    } else {
      r.x[k] = *p++;
    }
    r.y[k] = r.is_complex() ? std::complex<double>(p[0], p[1]) : std::complex<double>(p[0], 0.0);
  }
}

void parse_header_records(const std::vector<std::string>& lines, int first_line, const std::string& file,
                          Uff58Record& r) {
  for (int i = 0; i < 5; ++i) r.id[static_cast<std::size_t>(i)] = std::string(trim(lines[static_cast<std::size_t>(i)]));

  // Record 6: Format(2(I5,I10),2(1X,10A1,I10,I4)). Fixed widths: entity names may contain blanks.
  {
    const std::string_view l = lines[5];
    const LineContext at{file, first_line + 5, "record 6"};
    r.function_type = static_cast<int>(parse_integer(field(l, 0, 5), at, 1, "function type"));
    r.response_entity = std::string(field(l, 31, 10));
    r.response_node = static_cast<int>(parse_integer(field(l, 41, 10), at, 42, "response node"));
    r.response_direction = static_cast<int>(parse_integer(field(l, 51, 4), at, 52, "response direction"));
    r.reference_entity = std::string(field(l, 56, 10));
    r.reference_node = static_cast<int>(parse_integer(field(l, 66, 10), at, 67, "reference node"));
    r.reference_direction = static_cast<int>(parse_integer(field(l, 76, 4), at, 77, "reference direction"));
  }
  // Record 7: Format(3I10,3E13.5); read as numbers separated by blanks (some writers widen the exponent).
  {
    const LineContext at{file, first_line + 6, "record 7"};
    const auto tokens = fortran_number_tokens(lines[6]);
    if (tokens.size() < 5)
      throw DataError(file, at.line, 0,
                      "UFF 58 record 7 needs data type, number of points, spacing, abscissa minimum and increment");
    r.ordinate_data_type = static_cast<int>(parse_integer(tokens[0].first, at, tokens[0].second, "ordinate data type"));
    const long long points = parse_integer(tokens[1].first, at, tokens[1].second, "number of points");
    const long long spacing = parse_integer(tokens[2].first, at, tokens[2].second, "abscissa spacing");
    double reals[3] = {0, 0, 0};
    for (std::size_t i = 3; i < tokens.size() && i < 6; ++i) {
      const auto v = parse_number(tokens[i].first, true);
      if (!v || !std::isfinite(*v))
        throw DataError(file, at.line, tokens[i].second,
                        "UFF 58 record 7: " + shown(tokens[i].first) + " is not a finite number");
      reals[i - 3] = *v;
    }
    if (r.ordinate_data_type != 2 && r.ordinate_data_type != 4 && r.ordinate_data_type != 5 &&
        r.ordinate_data_type != 6)
      throw DataError(file, at.line, tokens[0].second,
                      "UFF 58 record 7: ordinate data type " + std::to_string(r.ordinate_data_type) +
                          " is not supported (2 real single, 4 real double, 5 complex single, 6 complex double)");
    if (points <= 0)
      throw DataError(file, at.line, tokens[1].second, "UFF 58 record 7: number of points must be positive");
    if (spacing != 0 && spacing != 1)
      throw DataError(file, at.line, tokens[2].second, "UFF 58 record 7: abscissa spacing must be 0 (uneven) or 1 (even)");
    r.points = static_cast<Eigen::Index>(points);
    r.even_spacing = spacing == 1;
    r.abscissa_min = reals[0];
    r.abscissa_increment = reals[1];
    r.z_value = reals[2];
    if (r.even_spacing && !(r.abscissa_increment > 0))
      throw DataError(file, at.line, tokens[4].second,
                      "UFF 58 record 7: the abscissa increment of evenly spaced data must be positive");
  }
  // Records 8 and 9: Format(I10,3I5,2(1X,20A1)).
  {
    const LineContext at8{file, first_line + 7, "record 8"};
    r.abscissa_type = static_cast<int>(parse_integer(field(lines[7], 0, 10), at8, 1, "specific data type"));
    r.abscissa_label = std::string(field(lines[7], 26, 20));
    r.abscissa_units = std::string(field(lines[7], 47, std::string_view::npos));
    const LineContext at9{file, first_line + 8, "record 9"};
    r.ordinate_type = static_cast<int>(parse_integer(field(lines[8], 0, 10), at9, 1, "specific data type"));
    r.ordinate_label = std::string(field(lines[8], 26, 20));
    r.ordinate_units = std::string(field(lines[8], 47, std::string_view::npos));
    // Record 10 was never needed to read data: a writer's odd one is taken as type 0, not refused.
    const LineContext at10{file, first_line + 9, "record 10"};
    try {
      r.ordinate_denominator_type =
          static_cast<int>(parse_integer(field(lines[9], 0, 10), at10, 1, "specific data type"));
    } catch (const DataError&) {
      r.ordinate_denominator_type = 0;
    }
    r.ordinate_denominator_label = std::string(field(lines[9], 26, 20));
    r.ordinate_denominator_units = std::string(field(lines[9], 47, std::string_view::npos));
  }
}

void read_ascii_body(Cursor& c, const std::string& file, Uff58Record& r) {
  const Eigen::Index expected = r.points * values_per_point(r);
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(std::min<Eigen::Index>(expected, 1 << 24)));
  std::string_view line;
  while (true) {
    // The end of the file closes the last dataset as well as a delimiter would.
    if (!c.next_line(line)) break;
    if (is_delimiter(line)) break;
    for (const auto& [token, column] : fortran_number_tokens(line)) {
      const auto v = parse_number(token, true);
      if (!v) throw DataError(file, c.line(), column, "UFF 58 data: " + shown(token) + " is not a number");
      if (!std::isfinite(*v))
        throw DataError(file, c.line(), column, "UFF 58 data: " + shown(token) + " is not finite");
      if (std::abs(*v) > kMaxDataMagnitude)
        throw DataError(file, c.line(), column, "UFF 58 data: " + too_large_message(token));
      if (static_cast<Eigen::Index>(values.size()) == expected)
        throw DataError(file, c.line(), column,
                        "UFF 58 data: more values than the " + std::to_string(expected) + " that record 7 declares (" +
                            std::to_string(r.points) + " points)");
      values.push_back(*v);
    }
  }
  if (static_cast<Eigen::Index>(values.size()) != expected)
    throw DataError(file, r.line, 0,
                    "UFF dataset 58 is cut off: record 7 declares " + std::to_string(r.points) + " points (" +
                        std::to_string(expected) + " values), the file holds " + std::to_string(values.size()) +
                        " values");
  fill_points(r, values);
}

void read_binary_body(Cursor& c, const std::string& file, Uff58Record& r, bool little_endian,
                      long long bytes) {
  const std::size_t size = (r.ordinate_data_type == 2 || r.ordinate_data_type == 5) ? 4 : 8;
  const Eigen::Index expected = r.points * values_per_point(r);
  if (bytes != static_cast<long long>(expected) * static_cast<long long>(size))
    throw DataError(file, r.line, 0,
                    "UFF dataset 58b: the header declares " + std::to_string(bytes) + " bytes, but " +
                        std::to_string(r.points) + " points need " + std::to_string(expected) + " values of " +
                        std::to_string(size) + " bytes");
  // Read in chunks as the file holds them: the declared count alone allocates nothing (a header may claim terabytes).
  const bool swap = little_endian != host_is_little_endian();
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(std::min<Eigen::Index>(expected, 1 << 24)));
  char chunk[1 << 16];  // a multiple of both value sizes
  long long left = bytes, held = 0;
  while (left > 0) {
    const auto want = static_cast<std::size_t>(std::min<long long>(left, static_cast<long long>(sizeof chunk)));
    const std::size_t got = c.take(chunk, want);
    held += static_cast<long long>(got);
    if (got < want)
      throw DataError(file, r.line, 0,
                      "UFF dataset 58b is cut off: the header declares " + std::to_string(bytes) +
                          " bytes of data, the file holds " + std::to_string(held));
    left -= static_cast<long long>(got);
    unsigned char raw[8];
    for (std::size_t at = 0; at < got; at += size) {
      std::memcpy(raw, chunk + at, size);
      if (swap)
        for (std::size_t j = 0; j < size / 2; ++j) std::swap(raw[j], raw[size - 1 - j]);
      double v;
      if (size == 4) {
        float f;
        std::memcpy(&f, raw, 4);
        v = f;
      } else {
        std::memcpy(&v, raw, 8);
      }
      const std::size_t i = values.size();
      if (!std::isfinite(v))
        throw DataError(file, r.line, 0, "UFF dataset 58b: value " + std::to_string(i + 1) + " is not finite");
      if (std::abs(v) > kMaxDataMagnitude)
        throw DataError(file, r.line, 0, "UFF dataset 58b: value " + std::to_string(i + 1) + " is too large: "
                                         "magnitudes above 1e150 are rejected (their squares overflow)");
      values.push_back(v);
    }
  }
  fill_points(r, values);
  std::string_view line;
  while (c.next_line(line)) {
    if (trim(line).empty()) continue;
    if (is_delimiter(line)) return;
    throw DataError(file, c.line(), 1, "UFF dataset 58b: expected '    -1' after the binary data, found " + shown(line));
  }
  throw DataError(file, r.line, 0, "UFF dataset 58b is not closed by a '    -1' line");
}

Uff58Record read_dataset_58(Cursor& c, const std::string& file, std::string_view number_line) {
  Uff58Record r;
  r.line = c.line();
  const auto tokens = fortran_number_tokens(number_line);
  r.binary = trim(tokens[0].first) == "58b";
  bool little_endian = true;
  long long bytes = 0;
  if (r.binary) {
    const LineContext at{file, r.line, "58b header"};
    if (tokens.size() < 5)
      throw DataError(file, r.line, 0,
                      "UFF 58b header line needs byte ordering, floating-point format, ASCII line count and byte count");
    const long long order = parse_integer(tokens[1].first, at, tokens[1].second, "byte ordering");
    const long long format = parse_integer(tokens[2].first, at, tokens[2].second, "floating-point format");
    const long long lines = parse_integer(tokens[3].first, at, tokens[3].second, "number of ASCII lines");
    bytes = parse_integer(tokens[4].first, at, tokens[4].second, "number of bytes");
    if (order != 1 && order != 2)
      throw DataError(file, r.line, tokens[1].second, "UFF 58b: byte ordering must be 1 (little endian) or 2 (big endian)");
    if (format != 2)
      throw DataError(file, r.line, tokens[2].second,
                      "UFF 58b: floating-point format " + std::to_string(format) + " is not supported (only 2, IEEE 754)");
    if (lines != 11)
      throw DataError(file, r.line, tokens[3].second, "UFF 58b: expected 11 ASCII header lines, the header says " +
                                                          std::to_string(lines));
    if (bytes < 0) throw DataError(file, r.line, tokens[4].second, "UFF 58b: negative byte count");
    little_endian = order == 1;
  }
  std::vector<std::string> header;
  std::string_view line;
  while (header.size() < 11) {
    if (!c.next_line(line) || is_delimiter(line))
      throw DataError(file, c.line(), 0,
                      "UFF dataset 58 ends after " + std::to_string(header.size()) + " of its 11 header lines");
    header.emplace_back(line);
  }
  parse_header_records(header, r.line + 1, file, r);
  if (r.binary)
    read_binary_body(c, file, r, little_endian, bytes);
  else
    read_ascii_body(c, file, r);
  return r;
}

}  // namespace

std::vector<Uff58Record> read_uff58(std::istream& in, const std::string& file_name) {
  Cursor c(in, file_name);
  std::vector<Uff58Record> records;
  std::string_view line;
  bool any_text = false;
  while (c.next_line(line)) {
    if (trim(line).empty()) continue;
    any_text = true;
    if (!is_delimiter(line))
      throw DataError(file_name, c.line(), 1, "expected '    -1' (start of a UFF dataset), found " + shown(line));
    if (!c.next_line(line)) break;  // a lone trailing delimiter
    const auto tokens = fortran_number_tokens(line);
    if (tokens.empty())
      throw DataError(file_name, c.line(), 1, "expected a UFF dataset number after '    -1'");
    const std::string number(tokens[0].first);  // the line's text is gone after the next line is read
    if (number == "58" || number == "58b") {
      records.push_back(read_dataset_58(c, file_name, line));
      continue;
    }
    if (!number.empty() && number.back() == 'b')
      throw DataError(file_name, c.line(), tokens[0].second,
                      "binary UFF dataset " + number + " is not supported (only 58 and 58b)");
    // Another ASCII dataset (units, header, geometry): skip to its closing delimiter.
    const int start = c.line();
    bool closed = false;
    while (c.next_line(line))
      if (is_delimiter(line)) {
        closed = true;
        break;
      }
    if (!closed) throw DataError(file_name, start, 0, "UFF dataset " + number + " is not closed by '    -1'");
  }
  if (!any_text) throw DataError(file_name, 0, 0, "empty file");
  if (records.empty()) throw DataError(file_name, 0, 0, "no UFF dataset 58 or 58b in the file");
  return records;
}

std::vector<Uff58Record> read_uff58(const std::string& path) {
  if (path == "-") return read_uff58(std::cin, path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path, 0, 0, "cannot open file");
  return read_uff58(in, path);
}

}  // namespace mbgen
