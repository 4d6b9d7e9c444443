// Reading datasets 55 (mode shapes at nodes), 15 (nodes) and 82 (trace lines) from a UFF file; every other dataset
// is skipped, binary
// 58b by its declared byte count (runtime/include/mbgen/data/uff55.hpp names the layout and where it comes from).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>

#include "mbgen/data/data_error.hpp"
#include "mbgen/data/uff55.hpp"
#include "text_parsing.hpp"

namespace mbgen {

using namespace data_detail;

namespace {

bool is_delimiter(std::string_view line) { return trim(line) == "-1"; }

std::string shown(std::string_view text) { return "'" + std::string(trim(text).substr(0, 40)) + "'"; }

class Lines {
 public:
  Lines(std::istream& in, const std::string& file) : reader_(in, file), file_(file) {}
  bool next(std::string& line) { return reader_.next(line); }
  // The next line of dataset `what`; DataError when the dataset or the file ends first.
  std::string required(const char* what, int start) {
    std::string line;
    if (!reader_.next(line) || is_delimiter(line))
      throw DataError(file_, reader_.line_number(), 0,
                      std::string("UFF dataset ") + what + " (line " + std::to_string(start) + ") ends too early");
    return line;
  }
  std::size_t take(char* out, std::size_t n) { return reader_.read_block(out, n); }
  int line() const { return reader_.line_number(); }
  const std::string& file() const { return file_; }

 private:
  LineReader reader_;
  std::string file_;
};

// The numbers of one line; `count` of them at least (0: any), integers when `integers`.
std::vector<double> numbers(Lines& c, const std::string& line, const char* record, std::size_t count, bool integers) {
  std::vector<double> out;
  for (const auto& [token, column] : fortran_number_tokens(line)) {
    const auto v = parse_number(token, true);
    if (!v || !std::isfinite(*v) || std::abs(*v) > kMaxDataMagnitude)
      throw DataError(c.file(), c.line(), column, std::string(record) + ": " + shown(token) + " is not a finite number");
    if (integers && (*v != std::floor(*v) || std::abs(*v) > 2e9))
      throw DataError(c.file(), c.line(), column, std::string(record) + ": " + shown(token) + " is not an integer");
    out.push_back(*v);
  }
  if (out.size() < count)
    throw DataError(c.file(), c.line(), 0,
                    std::string(record) + ": expected " + std::to_string(count) + " numbers, found " +
                        std::to_string(out.size()));
  return out;
}

// `count` real values that run over as many lines as they need (six a line in the specification).
std::vector<double> values(Lines& c, const char* record, std::size_t count, int start) {
  std::vector<double> out;
  while (out.size() < count) {
    const std::string line = c.required("55", start);
    for (const double v : numbers(c, line, record, 0, false)) out.push_back(v);
  }
  if (out.size() > count)
    throw DataError(c.file(), c.line(), 0,
                    std::string(record) + ": " + std::to_string(out.size()) + " values where " +
                        std::to_string(count) + " were due");
  return out;
}

Uff55Record read_55(Lines& c) {
  Uff55Record r;
  r.line = c.line();
  for (std::string& id : r.id) id = std::string(trim(c.required("55", r.line)));
  const std::vector<double> six = numbers(c, c.required("55", r.line), "UFF 55 record 6", 6, true);
  const int record6 = c.line();
  r.model_type = static_cast<int>(six[0]);
  r.analysis_type = static_cast<int>(six[1]);
  r.data_characteristic = static_cast<int>(six[2]);
  r.specific_data_type = static_cast<int>(six[3]);
  const int data_type = static_cast<int>(six[4]), per_node = static_cast<int>(six[5]);
  if (r.analysis_type != 2 && r.analysis_type != 3 && r.analysis_type != 7)
    throw DataError(c.file(), record6, 0,
                    "UFF 55 record 6: analysis type " + std::to_string(r.analysis_type) +
                        " is not a mode (2 normal mode, 3 or 7 complex mode are read)");
  if (r.data_characteristic < 1 || r.data_characteristic > 3)
    throw DataError(c.file(), record6, 0,
                    "UFF 55 record 6: data characteristic " + std::to_string(r.data_characteristic) +
                        " is not read (1 scalar, 2 three translations, 3 six values per node)");
  if (data_type != 2 && data_type != 5)
    throw DataError(c.file(), record6, 0,
                    "UFF 55 record 6: data type " + std::to_string(data_type) + " is neither 2 (real) nor 5 (complex)");
  if (per_node != r.values_per_node())
    throw DataError(c.file(), record6, 0,
                    "UFF 55 record 6: " + std::to_string(per_node) + " values per node, but data characteristic " +
                        std::to_string(r.data_characteristic) + " has " + std::to_string(r.values_per_node()));
  r.complex = data_type == 5;
  // Record 7: the counts of record 7's integers and record 8's reals, then the integers (8 a line).
  std::vector<double> ints = numbers(c, c.required("55", r.line), "UFF 55 record 7", 2, true);
  const double n_int = ints[0], n_real = ints[1];
  if (n_int < 2 || n_int > 10 || n_real < 1 || n_real > 12)
    throw DataError(c.file(), c.line(), 0,
                    "UFF 55 record 7: 2 to 10 integer and 1 to 12 real values expected, the record says " +
                        std::to_string(static_cast<int>(n_int)) + " and " + std::to_string(static_cast<int>(n_real)));
  while (ints.size() < 2 + static_cast<std::size_t>(n_int)) {
    const auto more = numbers(c, c.required("55", r.line), "UFF 55 record 7", 1, true);
    ints.insert(ints.end(), more.begin(), more.end());
  }
  r.load_case = static_cast<int>(ints[2]);
  r.mode_number = static_cast<int>(ints[3]);
  const std::size_t reals_due = static_cast<std::size_t>(n_real);
  if (reals_due < (r.analysis_type == 2 ? 1u : 2u))
    throw DataError(c.file(), c.line(), 0, "UFF 55 record 7: too few real values for the mode's record 8");
  const std::vector<double> reals = values(c, "UFF 55 record 8", reals_due, r.line);
  const auto real = [&](std::size_t i) { return i < reals.size() ? reals[i] : 0.0; };
  if (r.analysis_type == 2) {
    r.frequency_hz = real(0);
    r.modal_mass = real(1);
    r.viscous_damping = real(2);
    r.hysteretic_damping = real(3);
  } else {
    r.eigenvalue = {real(0), real(1)};
    r.modal_a = {real(2), real(3)};
    r.modal_b = {real(4), real(5)};
  }
  // Records 9 and 10, per node, up to the closing delimiter.
  const std::size_t per = static_cast<std::size_t>(per_node) * (r.complex ? 2 : 1);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (true) {
    if (!c.next(line)) throw DataError(c.file(), r.line, 0, "UFF dataset 55 is not closed by '    -1'");
    if (is_delimiter(line)) break;
    if (trim(line).empty()) continue;
    const std::vector<double> node = numbers(c, line, "UFF 55 record 9 (node number)", 1, true);
    if (node.size() != 1)
      throw DataError(c.file(), c.line(), 0,
                      "UFF 55 record 9: a node number alone on its line expected, found " + shown(line));
    r.nodes.push_back(static_cast<int>(node[0]));
    rows.push_back(values(c, "UFF 55 record 10 (the node's values)", per, r.line));
  }
  if (r.nodes.empty()) throw DataError(c.file(), r.line, 0, "UFF dataset 55 holds no node");
  r.values.resize(static_cast<Eigen::Index>(rows.size()), per_node);
  for (std::size_t n = 0; n < rows.size(); ++n)
    for (int k = 0; k < per_node; ++k) {
      const std::size_t at = static_cast<std::size_t>(k) * (r.complex ? 2 : 1);
      r.values(static_cast<Eigen::Index>(n), k) = {rows[n][at], r.complex ? rows[n][at + 1] : 0.0};
    }
  return r;
}

void read_15(Lines& c, std::vector<Uff15Node>& nodes) {
  const int start = c.line();
  std::string line;
  while (true) {
    if (!c.next(line)) throw DataError(c.file(), start, 0, "UFF dataset 15 is not closed by '    -1'");
    if (is_delimiter(line)) return;
    if (trim(line).empty()) continue;
    const std::vector<double> v = numbers(c, line, "UFF 15 record 1", 7, false);
    const bool integers = std::all_of(v.begin(), v.begin() + 4, [](double x) {
      return x == std::floor(x) && std::abs(x) <= 2e9;  // fits an int
    });
    if (v.size() != 7 || !integers)
      throw DataError(c.file(), c.line(), 0,
                      "UFF 15 record 1: expected node, two coordinate systems, colour, x, y, z; found " + shown(line));
    Uff15Node n;
    n.node = static_cast<int>(v[0]);
    n.definition_cs = static_cast<int>(v[1]);
    n.displacement_cs = static_cast<int>(v[2]);
    n.colour = static_cast<int>(v[3]);
    n.xyz = {v[4], v[5], v[6]};
    n.line = c.line();
    nodes.push_back(n);
  }
}

// Record 3 is read to the closing delimiter, whatever record 1's count: writers count differently (pyuff counts the
// changes of node, not the entries).
void read_82(Lines& c, std::vector<Uff82TraceLine>& traces) {
  Uff82TraceLine t;
  t.line = c.line();
  const std::vector<double> head = numbers(c, c.required("82", t.line), "UFF 82 record 1", 3, true);
  t.number = static_cast<int>(head[0]);
  t.colour = static_cast<int>(head[2]);
  t.id = std::string(trim(c.required("82", t.line)));
  std::string line;
  while (true) {
    if (!c.next(line)) throw DataError(c.file(), t.line, 0, "UFF dataset 82 is not closed by '    -1'");
    if (is_delimiter(line)) break;
    for (const double v : numbers(c, line, "UFF 82 record 3", 0, true)) {
      if (v < 0) throw DataError(c.file(), c.line(), 0, "UFF 82 record 3: a node number is >= 0");
      t.nodes.push_back(static_cast<int>(v));
    }
  }
  traces.push_back(std::move(t));
}

// A binary 58b: its header line declares the bytes after its 11 ASCII lines.
void skip_58b(Lines& c, const std::string& number_line) {
  const int start = c.line();
  const auto tokens = fortran_number_tokens(number_line);
  const auto bytes = tokens.size() >= 5 ? parse_number(tokens[4].first) : std::nullopt;
  if (!bytes || *bytes < 0 || *bytes != std::floor(*bytes))
    throw DataError(c.file(), start, 0, "UFF 58b header line: no byte count");
  for (int i = 0; i < 11; ++i) c.required("58b", start);
  char chunk[1 << 16];
  for (double left = *bytes; left > 0;) {
    const std::size_t want = static_cast<std::size_t>(std::min<double>(left, sizeof chunk));
    if (c.take(chunk, want) < want) throw DataError(c.file(), start, 0, "UFF dataset 58b is cut off");
    left -= static_cast<double>(want);
  }
  std::string line;
  while (c.next(line))
    if (is_delimiter(line)) return;
  throw DataError(c.file(), start, 0, "UFF dataset 58b is not closed by '    -1'");
}

struct Contents {
  std::vector<Uff55Record> modes;
  std::vector<Uff15Node> nodes;
  std::vector<Uff82TraceLine> traces;
};

// Datasets 82 are read only when `traces` is asked for; the modes' reader skips them as any other dataset.
Contents scan(std::istream& in, const std::string& file, bool traces = false) {
  Lines c(in, file);
  Contents out;
  std::string line;
  bool any_text = false;
  while (c.next(line)) {
    if (trim(line).empty()) continue;
    any_text = true;
    if (!is_delimiter(line))
      throw DataError(file, c.line(), 1, "expected '    -1' (start of a UFF dataset), found " + shown(line));
    if (!c.next(line)) break;  // a lone trailing delimiter
    const auto tokens = fortran_number_tokens(line);
    if (tokens.empty()) throw DataError(file, c.line(), 1, "expected a UFF dataset number after '    -1'");
    const std::string number(tokens[0].first);
    if (number == "55") {
      out.modes.push_back(read_55(c));
    } else if (number == "15") {
      read_15(c, out.nodes);
    } else if (number == "82" && traces) {
      read_82(c, out.traces);
    } else if (number == "58b") {
      skip_58b(c, line);
    } else if (!number.empty() && number.back() == 'b') {
      throw DataError(file, c.line(), 1, "binary UFF dataset " + number + " cannot be skipped (only 58b)");
    } else {
      const int start = c.line();
      bool closed = false;
      while (!closed && c.next(line)) closed = is_delimiter(line);
      if (!closed) throw DataError(file, start, 0, "UFF dataset " + number + " is not closed by '    -1'");
    }
  }
  if (!any_text) throw DataError(file, 0, 0, "empty file");
  return out;
}

}  // namespace

std::vector<Uff55Record> read_uff55(std::istream& in, const std::string& file_name) {
  Contents contents = scan(in, file_name);
  if (contents.modes.empty()) throw DataError(file_name, 0, 0, "no UFF dataset 55 (modes at nodes) in the file");
  return std::move(contents.modes);
}

std::vector<Uff55Record> read_uff55(const std::string& path) {
  if (path == "-") return read_uff55(std::cin, path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path, 0, 0, "cannot open file");
  return read_uff55(in, path);
}

std::vector<Uff15Node> read_uff15(std::istream& in, const std::string& file_name) {
  return scan(in, file_name).nodes;
}

std::vector<Uff82TraceLine> read_uff82(std::istream& in, const std::string& file_name) {
  return scan(in, file_name, true).traces;
}

}  // namespace mbgen
