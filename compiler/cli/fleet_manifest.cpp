// Reading a fleet manifest (fleet_manifest.hpp, docs/fleets.md).
#include "cli/fleet_manifest.hpp"

#include <mbgen/estimation/fit.hpp>

#include <CLI/CLI.hpp>
#include <glob.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "frontend/message.hpp"

namespace mbgen::cli {

namespace fs = std::filesystem;

namespace {

template <typename... Args>
[[noreturn]] void fail(const std::string& file, int line, int column, fmt::format_string<Args...> format,
                       Args&&... args) {
  throw FitError(frontend::error_text(file, ir::SourceLoc{line, column}, format, std::forward<Args>(args)...));
}

// Splits a CSV line on commas (no quoting: names, paths and globs in a manifest need none), keeping each field's
// 1-based column.
std::vector<std::pair<std::string, int>> fields(const std::string& line) {
  std::vector<std::pair<std::string, int>> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string f = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    std::size_t lead = f.find_first_not_of(" \t");
    const std::size_t end = f.find_last_not_of(" \t\r");
    f = lead == std::string::npos ? "" : f.substr(lead, end - lead + 1);
    if (lead == std::string::npos) lead = 0;
    out.emplace_back(f, static_cast<int>(start + lead + 1));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

bool valid_machine_name(const std::string& s) {
  if (s.empty() || s[0] == '.') return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return true;
}

std::vector<std::string> expand(const std::string& pattern) {
  glob_t g{};
  const int rc = ::glob(pattern.c_str(), GLOB_ERR, nullptr, &g);
  std::vector<std::string> out;
  if (rc == 0)
    for (std::size_t i = 0; i < g.gl_pathc; ++i) out.emplace_back(g.gl_pathv[i]);
  globfree(&g);
  return out;  // glob sorts its matches (no GLOB_NOSORT)
}

}  // namespace

std::vector<FleetItem> read_fleet_manifest(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw FitError(frontend::error_text(path, "is a directory, not a manifest"));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FitError(frontend::error_text(path, "cannot read the manifest"));
  const fs::path base = fs::path(path).parent_path();
  auto resolve = [&](const std::string& p) { return fs::path(p).is_absolute() || base.empty() ? p : (base / p).string(); };

  std::vector<FleetItem> items;
  std::set<std::string> names;
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a UTF-8 byte order mark
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto f = fields(line);
    if (!header) {
      if (f.size() != 3 || f[0].first != "machine" || f[1].first != "model" || f[2].first != "data")
        fail(path, number, 1, "the header must be `machine,model,data`");
      header = true;
      continue;
    }
    if (f.size() != 3) fail(path, number, 1, "expected 3 fields (machine,model,data), found {}", f.size());
    FleetItem item;
    item.line = number;
    item.machine = f[0].first;
    if (!valid_machine_name(item.machine))
      fail(path, number, f[0].second,
           "machine `{}`: a name of letters, digits, `_`, `-` and `.` (not first) is needed: it names the output "
           "directory",
           item.machine);
    if (!names.insert(item.machine).second)
      fail(path, number, f[0].second, "machine `{}` is listed twice", item.machine);
    if (f[1].first.empty()) fail(path, number, f[1].second, "no model");
    item.model = resolve(f[1].first);
    std::istringstream patterns(f[2].first);
    std::string pattern;
    int column = f[2].second;
    while (std::getline(patterns, pattern, ';')) {
      const std::vector<std::string> files = expand(resolve(pattern));
      if (files.empty()) fail(path, number, column, "`{}` matches no file", pattern);
      item.data.insert(item.data.end(), files.begin(), files.end());
      column += static_cast<int>(pattern.size()) + 1;
    }
    if (item.data.empty()) fail(path, number, f[2].second, "no data");
    items.push_back(std::move(item));
  }
  if (!header) throw FitError(frontend::error_text(path, "empty manifest (expected the header `machine,model,data`)"));
  if (items.empty()) throw FitError(frontend::error_text(path, "the manifest lists no machine"));
  return items;
}

const FleetItem& select_fleet_item(const std::vector<FleetItem>& items, const std::string& selector) {
  for (const FleetItem& item : items)
    if (item.machine == selector) return item;
  if (!selector.empty() && selector.find_first_not_of("0123456789") == std::string::npos && selector.size() < 10) {
    const std::size_t index = std::stoul(selector);
    if (index < items.size()) return items[index];
  }
  throw CLI::ValidationError("--item", "`" + selector + "` is neither a machine of the manifest nor an index below " +
                                           std::to_string(items.size()));
}

std::string file_digest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FitError(frontend::error_text(path, "cannot read"));
  std::uint64_t h = 14695981039346656037ull;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buffer[i]);
      h *= 1099511628211ull;
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace mbgen::cli
