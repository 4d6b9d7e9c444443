// One measured data set, whatever its file format: a time record or FRFs.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "mbgen/data/data_settings.hpp"
#include "mbgen/data/frf_data.hpp"
#include "mbgen/data/time_record.hpp"
#include "mbgen/data/uff.hpp"

namespace mbgen {

// A measured signal (an FRF channel, a record's output, a record's inputs together) none of whose values exceeds
// this in magnitude, though not all zero, has squares below the smallest normal double: its sum of squares is 0 and a
// normalized error NaN (or, in the modal analysis, a perfect 0). The fit and the modal analysis refuse it. The
// counterpart of the readers' largest magnitude, 1e150; no measurement in any unit comes near either.
constexpr double kMinSignalMagnitude = 1e-150;

// One measured data set, as a data file holds it: an FRF table or a time record, each with its file name and its
// `# set` values (which override parameters for this data set alone). What the readers return and the estimators take.
struct DataSet {
  std::variant<FrfData, TimeRecord> content;
  DataSet(FrfData frf) : content(std::move(frf)) {}         // NOLINT: implicit on purpose
  DataSet(TimeRecord record) : content(std::move(record)) {}  // NOLINT
  const std::string& file() const;
  const SetMap& set() const;
  bool is_frf() const { return std::holds_alternative<FrfData>(content); }
};

// Reads a data file of any supported kind (docs/data.md):
// - UFF 58/58b when the name ends in .uff or .unv (any case) or the first non-blank line is "-1". The
//   points map to channels through `uff_mapping`, or else through the mapping file PATH.map when it exists,
//   or else get default names ("node1:+X").
// - CSV otherwise: a time record when the header's first column is `t`, FRFs when it is `f_hz`.
// PATH "-" reads standard input (a UFF mapping must then be passed explicitly). Throws DataError.
DataSet read_data_file(const std::string& path, const std::optional<ChannelNames>& known = std::nullopt,
                      const std::optional<UffMapping>& uff_mapping = std::nullopt);
DataSet read_data_file(const std::string& path, const std::vector<std::string>& known_inputs,
                      const std::vector<std::string>& known_outputs);
// The same from a stream; `file_name` serves the messages and the UFF-by-extension rule.
DataSet read_data(std::istream& in, const std::string& file_name,
                  const std::optional<ChannelNames>& known = std::nullopt,
                  const std::optional<UffMapping>& uff_mapping = std::nullopt);

}  // namespace mbgen
