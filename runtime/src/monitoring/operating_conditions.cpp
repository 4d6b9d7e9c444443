// Reading `# condition NAME=VALUE` lines (runtime/include/mbgen/monitoring/operating_conditions.hpp).
#include "mbgen/monitoring/operating_conditions.hpp"

#include "mbgen/data/data_error.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace mbgen {

namespace {

bool is_uff_name(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".uff" || ext == ".unv";
}

bool space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
bool name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// A decimal number as the CSV data are written: sign, digits, a point, an exponent; no hex, inf or nan.
bool decimal(const std::string& s) {
  if (s.empty() || s.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(v);
}

}  // namespace

std::vector<ConditionValue> read_operating_conditions(const std::string& path) {
  std::vector<ConditionValue> out;
  if (path == "-" || is_uff_name(path)) return out;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path, 0, 0, "cannot open the file");
  static const std::string keyword = "condition";
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::size_t pos = 0;
    while (pos < line.size() && space(line[pos])) ++pos;
    if (pos == line.size()) continue;
    if (line.compare(pos, 2, "-1") == 0 && line.find_first_not_of(" \t", pos + 2) == std::string::npos)
      return {};                       // a UFF file by its content
    if (line[pos] != '#') break;       // the header: the preamble is over
    ++pos;
    while (pos < line.size() && space(line[pos])) ++pos;
    if (line.compare(pos, keyword.size(), keyword) != 0) continue;  // another comment
    const std::size_t after = pos + keyword.size();
    if (after < line.size() && !space(line[after])) continue;        // a word such as "conditioned": a comment
    pos = after;
    while (pos < line.size() && space(line[pos])) ++pos;
    const int column = static_cast<int>(pos) + 1;
    std::size_t end = line.size();
    while (end > pos && space(line[end - 1])) --end;
    const std::string item = line.substr(pos, end - pos);
    const std::size_t eq = item.find('=');
    if (item.empty() || eq == std::string::npos)
      throw DataError(path, number, column,
                      "bad '# condition' line: expected NAME=VALUE, e.g. '# condition temperature=21.5'");
    const std::string name = item.substr(0, eq);
    const std::string value = item.substr(eq + 1);
    if (name.empty() || !name_start(name[0]) || !std::all_of(name.begin(), name.end(), name_char))
      throw DataError(path, number, column,
                      "bad '# condition' line: '" + name + "' is not a name (a letter or _, then letters, digits, _)");
    if (!decimal(value))
      throw DataError(path, number, column + static_cast<int>(eq) + 1,
                      "bad '# condition' line: '" + value + "' is not a finite decimal number");
    for (const ConditionValue& c : out)
      if (c.name == name)
        throw DataError(path, number, column,
                        "a second '# condition " + name + "=' line (the first is on line " + std::to_string(c.line) +
                            ")");
    out.push_back({name, std::strtod(value.c_str(), nullptr), number});
  }
  return out;
}

ConditionTable condition_table(const std::vector<std::string>& paths,
                               const std::vector<std::vector<ConditionValue>>& per_file) {
  ConditionTable t;
  if (per_file.empty()) return t;
  for (const ConditionValue& c : per_file.front()) t.names.push_back(c.name);
  for (std::size_t f = 0; f < per_file.size(); ++f) {
    std::vector<double> values;
    for (const std::string& name : t.names) {
      const auto it = std::find_if(per_file[f].begin(), per_file[f].end(),
                                   [&](const ConditionValue& c) { return c.name == name; });
      if (it == per_file[f].end())
        throw DataError(paths[f], 0, 0,
                        "no '# condition " + name + "=' line, but " + paths.front() +
                            " has one: every data set must give the same conditions");
      values.push_back(it->value);
    }
    for (const ConditionValue& c : per_file[f])
      if (std::find(t.names.begin(), t.names.end(), c.name) == t.names.end())
        throw DataError(paths[f], c.line, 0,
                        "'# condition " + c.name + "=' is not given in " + paths.front() +
                            ": every data set must give the same conditions");
    t.values.push_back(std::move(values));
  }
  return t;
}

}  // namespace mbgen
