// One measured data set, whatever its file format: a time record or FRFs.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "mbgen/data_settings.hpp"
#include "mbgen/frf_data.hpp"
#include "mbgen/time_record.hpp"
#include "mbgen/uff.hpp"

namespace mbgen {

// What a data file holds. (The estimator wraps it as mbgen::DataSet, fit.hpp, with the data set's `# set` values.)
using DataFile = std::variant<TimeRecord, FrfData>;

// Reads a data file of any supported kind (docs/data.md):
// - UFF 58/58b when the name ends in .uff or .unv (any case) or the first non-blank line is "-1". The
//   points map to channels through `uff_mapping`, or else through the mapping file PATH.map when it exists,
//   or else get default names ("node1:+X").
// - CSV otherwise: a time record when the header's first column is `t`, FRFs when it is `f_hz`.
// PATH "-" reads standard input (a UFF mapping must then be passed explicitly). Throws DataError.
DataFile read_data_file(const std::string& path, const std::optional<ChannelNames>& known = std::nullopt,
                       const std::optional<UffMapping>& uff_mapping = std::nullopt);
DataFile read_data_file(const std::string& path, const std::vector<std::string>& known_inputs,
                       const std::vector<std::string>& known_outputs);
// The same from a stream; `file_name` serves the messages and the UFF-by-extension rule.
DataFile read_data(std::istream& in, const std::string& file_name,
                  const std::optional<ChannelNames>& known = std::nullopt,
                  const std::optional<UffMapping>& uff_mapping = std::nullopt);

const std::string& data_file(const DataFile& data);
const SetMap& data_set_values(const DataFile& data);

}  // namespace mbgen
