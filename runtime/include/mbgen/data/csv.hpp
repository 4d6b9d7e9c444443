// CSV time records and FRFs, in the formats of docs/interfaces.md ("Measured data"); details in docs/data.md.
//
// Readers validate strictly and throw DataError naming file, line and column (the 1-based field index,
// with the column's name). `file_name` is used for messages only; "-" conventionally means standard input.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

#include "mbgen/data/data_settings.hpp"
#include "mbgen/data/frf_data.hpp"
#include "mbgen/data/time_record.hpp"

namespace mbgen {

// Time record: header `t,SIGNAL,...`. With `known`, every signal must be a model input or output.
TimeRecord read_time_record_csv(std::istream& in, const std::string& file_name,
                                const std::optional<ChannelNames>& known = std::nullopt);
TimeRecord read_time_record_csv(const std::string& path,
                                const std::optional<ChannelNames>& known = std::nullopt);

// FRF: header `f_hz,OUT/IN.re,OUT/IN.im[,OUT/IN.coh],...`. With `known`, OUT must be a model output and IN
// a model input.
FrfData read_frf_csv(std::istream& in, const std::string& file_name,
                     const std::optional<ChannelNames>& known = std::nullopt);
FrfData read_frf_csv(const std::string& path, const std::optional<ChannelNames>& known = std::nullopt);

// Writers: `# set` and `# hold=none` lines, the header, then one row per sample or frequency. Numbers are
// written in the shortest form that reads back to the same double, so a write/read round trip is exact.
void write_time_record_csv(std::ostream& out, const TimeRecord& record);
void write_frf_csv(std::ostream& out, const FrfData& frf);

}  // namespace mbgen
