// Reading and ordering by `# time=` lines (runtime/include/mbgen/monitoring/measurement_time.hpp).
#include "mbgen/monitoring/measurement_time.hpp"

#include "mbgen/data/data_error.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <numeric>

namespace mbgen {

namespace {

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

// Reads `digits` decimal digits at s[pos], advancing pos; -1 when they are not there.
long digits(const std::string& s, std::size_t& pos, int count) {
  long v = 0;
  for (int i = 0; i < count; ++i, ++pos) {
    if (pos >= s.size() || !std::isdigit(static_cast<unsigned char>(s[pos]))) return -1;
    v = v * 10 + (s[pos] - '0');
  }
  return v;
}

bool take(const std::string& s, std::size_t& pos, char c) {
  if (pos < s.size() && s[pos] == c) {
    ++pos;
    return true;
  }
  return false;
}

// Days from 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil).
long days_from_civil(long y, long m, long d) {
  y -= m <= 2;
  const long era = (y >= 0 ? y : y - 399) / 400;
  const long yoe = y - era * 400;
  const long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

bool leap(long y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

bool is_uff_name(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".uff" || ext == ".unv";
}

}  // namespace

std::optional<MeasurementTime> parse_measurement_time(const std::string& text) {
  const std::string& s = text;
  std::size_t pos = 0;
  const long year = digits(s, pos, 4);
  if (year < 0 || !take(s, pos, '-')) return std::nullopt;
  const long month = digits(s, pos, 2);
  if (month < 1 || month > 12 || !take(s, pos, '-')) return std::nullopt;
  const long day = digits(s, pos, 2);
  static const int month_days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (day < 1 || day > month_days[month - 1] + (month == 2 && leap(year))) return std::nullopt;
  long hour = 0, minute = 0, second = 0, offset = 0;
  double fraction = 0;
  if (take(s, pos, 'T')) {
    hour = digits(s, pos, 2);
    if (hour < 0 || hour > 23 || !take(s, pos, ':')) return std::nullopt;
    minute = digits(s, pos, 2);
    if (minute < 0 || minute > 59) return std::nullopt;
    if (take(s, pos, ':')) {
      second = digits(s, pos, 2);
      if (second < 0 || second > 60) return std::nullopt;  // 60: a leap second
      if (take(s, pos, '.')) {
        double scale = 0.1;
        const std::size_t start = pos;
        while (pos < s.size() && std::isdigit(static_cast<unsigned char>(s[pos]))) {
          fraction += scale * (s[pos] - '0');
          scale /= 10;
          ++pos;
        }
        if (pos == start) return std::nullopt;
      }
    }
    if (take(s, pos, 'Z')) {
    } else if (pos < s.size() && (s[pos] == '+' || s[pos] == '-')) {
      const int sign = s[pos] == '-' ? -1 : 1;
      ++pos;
      const long oh = digits(s, pos, 2);
      if (oh < 0 || oh > 23 || !take(s, pos, ':')) return std::nullopt;
      const long om = digits(s, pos, 2);
      if (om < 0 || om > 59) return std::nullopt;
      offset = sign * (oh * 3600 + om * 60);
    }
  }
  if (pos != s.size()) return std::nullopt;
  MeasurementTime t;
  t.text = text;
  // A zone +01:00 means local time one hour ahead of UTC: UTC = local - offset.
  t.seconds = static_cast<double>(days_from_civil(year, month, day) * 86400 + hour * 3600 + minute * 60 + second -
                                  offset) +
              fraction;
  return t;
}

std::optional<MeasurementTime> read_measurement_time(const std::string& path) {
  if (path == "-" || is_uff_name(path)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path, 0, 0, "cannot open the file");
  std::optional<MeasurementTime> found;
  int found_line = 0;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string text = trim(line);
    if (text.empty()) continue;
    if (text == "-1") return std::nullopt;  // a UFF file by its content
    if (text.front() != '#') break;          // the header: the preamble is over
    const std::string body = trim(text.substr(1));
    const std::size_t eq = body.find('=');
    if (eq == std::string::npos || trim(body.substr(0, eq)) != "time") continue;  // another comment
    if (found)
      throw DataError(path, number, 0,
                      "a second '# time=' line (the first is on line " + std::to_string(found_line) + ")");
    const std::string value = trim(body.substr(eq + 1));
    found = parse_measurement_time(value);
    if (!found)
      throw DataError(path, number, 0,
                      "bad '# time=' line: '" + value + "' is not an ISO 8601 date and time such as "
                      "2026-03-07T08:00:00Z");
    found_line = number;
  }
  return found;
}

std::vector<std::size_t> time_order(const std::vector<std::string>& paths,
                                    const std::vector<std::optional<MeasurementTime>>& times) {
  std::vector<std::size_t> order(paths.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto dated = std::count_if(times.begin(), times.end(), [](const auto& t) { return t.has_value(); });
  if (dated == 0) return order;
  if (static_cast<std::size_t>(dated) != times.size()) {
    for (std::size_t i = 0; i < times.size(); ++i)
      if (!times[i])
        throw DataError(paths[i], 0, 0,
                        "no '# time=' line, but other data sets have one: it cannot be placed in time (give every "
                        "data set a time, or none, to use the argument order)");
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return times[a]->seconds < times[b]->seconds; });
  return order;
}

}  // namespace mbgen
