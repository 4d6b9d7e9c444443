// Measured data written in the formats mbgen reads (`mbgen convert`, mbgen.write_data): CSV (FRFs or a time
// record) or ASCII UFF 58 (FRFs, with the mapping file OUT.map beside them). docs/data.md, "Writing data".
#pragma once

#include <mbgen/data/data_set.hpp>

#include <optional>
#include <string>
#include <vector>

namespace mbgen::cli {

enum class DataFormat { Csv, Uff };

// The format a destination's name asks for: .csv, or .uff / .unv (any case); nullopt for another name.
std::optional<DataFormat> data_format_of(const std::string& path);

// How the written data take their UFF points and ordinate type (frf_uff58.hpp, UffPointRules).
struct DataWriteRequest {
  DataFormat format = DataFormat::Csv;
  std::string model_path;          // "": none; else its sensor points and output kinds
  std::vector<std::string> sets;   // with a model: --set NAME=VALUE (the points' places)
  std::string quantity = "auto";   // auto (the model's outputs, else the data's), receptance, mobility, accelerance
  std::vector<UffMapping> mappings;  // the data's own mapping files
  std::string title = "mbgen convert";  // UFF ID line 1 and the mapping file's heading
  std::vector<std::string> comments;    // CSV: lines before the data's own (`# time=...`, carried_comments)
};

// A data file's text, and for UFF the mapping file's (empty for CSV).
struct DataTexts {
  std::string data, mapping;
};

// `data` in `request.format`: a time record as CSV only (DataError for UFF: mbgen reads UFF time responses but does
// not write them).
DataTexts data_texts(const DataSet& data, const DataWriteRequest& request);

// The mapping files (PATH.map) beside those of `paths` that are read as UFF (by the name, or a first line "-1").
std::vector<UffMapping> own_mappings(const std::vector<std::string>& paths);

// The `# time=` and `# condition NAME=VALUE` lines of the CSV files at `paths` (read_measurement_time,
// read_operating_conditions), which the data readers skip as comments, for a CSV written from them: the same in every
// file that has them (DataError naming the file whose differ from the first's: one file is one measurement).
std::vector<std::string> carried_comments(const std::vector<std::string>& paths);

// The data files at `paths` read as `fit --data` reads them (with `model_path`: channels checked against its inputs
// and outputs, `# set` lines against its parameters and `sets`), as one data set: FRF files with the same lines and
// distinct channels are joined (their `set` values must agree); a time record stands alone. The UFF files' own
// mapping files (PATH.map) are added to `mappings`.
DataSet read_for_writing(const std::vector<std::string>& paths, const std::string& model_path,
                         const std::vector<std::string>& sets, std::vector<UffMapping>& mappings);

}  // namespace mbgen::cli
