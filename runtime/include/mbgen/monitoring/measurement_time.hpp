// When a data set was measured: the `# time=2026-03-07T08:00:00Z` line before a CSV header (docs/interfaces.md,
// "Measured data"), which `monitor` orders its data sets by. The data readers take the line for a free comment;
// this reads it on its own.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace mbgen {

struct MeasurementTime {
  std::string text;    // as written
  double seconds = 0;  // since 1970-01-01T00:00:00Z, for ordering
};

// ISO 8601 date and time: YYYY-MM-DD, optionally followed by THH:MM, :SS, a fraction .fff, and a zone Z or
// +HH:MM / -HH:MM (none: read as UTC). std::nullopt when `text` is not of this form or not a valid date.
std::optional<MeasurementTime> parse_measurement_time(const std::string& text);

// The `# time=` line among the comment lines before the header of the CSV file at `path`; std::nullopt when there
// is none, for standard input ("-": it cannot be read twice) and for UFF files (they carry no such line). Throws
// DataError (file and line) for a malformed time or a second `# time=` line.
std::optional<MeasurementTime> read_measurement_time(const std::string& path);

// The order to process data sets in: by time when every one has one (ties and equal times in argument order),
// argument order when none has. Throws DataError naming the first file without a time when only some have one:
// it could not be placed.
std::vector<std::size_t> time_order(const std::vector<std::string>& paths,
                                    const std::vector<std::optional<MeasurementTime>>& times);

}  // namespace mbgen
