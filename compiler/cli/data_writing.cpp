#include "cli/data_writing.hpp"

#include <mbgen/data/csv.hpp>
#include <mbgen/data/data_error.hpp>
#include <mbgen/monitoring/measurement_time.hpp>
#include <mbgen/monitoring/operating_conditions.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "cli/commands.hpp"
#include "cli/frf_uff58.hpp"
#include "cli/load_data.hpp"
#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"
#include "symbolic/derive.hpp"

namespace mbgen::cli {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// As read_data_file tells UFF from CSV: by the name, or a first non-blank line "-1".
bool read_as_uff(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".uff" || ext == ".unv") return true;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    const auto last = line.find_last_not_of(" \t\r");
    return line.substr(first, last - first + 1) == "-1";
  }
  return false;
}

int specific_data_type(ir::OutputKind kind) {
  return kind == ir::OutputKind::Acceleration ? 12 : kind == ir::OutputKind::Velocity ? 11 : 8;
}

FrfData joined(std::vector<FrfData> files) {
  FrfData out = std::move(files.front());
  std::vector<std::string> origin(out.channels.size(), out.file);  // each channel's file
  for (std::size_t k = 1; k < files.size(); ++k) {
    FrfData& more = files[k];
    if (more.f_hz.size() != out.f_hz.size() || more.f_hz != out.f_hz)
      throw DataError(more.file, 0, 0, "its frequency lines differ from those of " + out.file +
                                           ": FRF files written into one file must share their lines");
    const auto text = [](const SetMap& s) {
      std::string t;
      for (const auto& [name, value] : s) t += name + "=" + value.text + ";";
      return t;
    };
    if (text(more.set) != text(out.set))
      throw DataError(more.file, 0, 0, "its `set` values differ from those of " + out.file +
                                           ": one file holds one data set, convert them one by one");
    for (FrfChannel& c : more.channels) {
      for (std::size_t i = 0; i < out.channels.size(); ++i)
        if (out.channels[i].output == c.output && out.channels[i].input == c.input)
          throw DataError(more.file, 0, 0, "the FRF " + c.output + "/" + c.input + " is in " + origin[i] + " already");
      out.channels.push_back(std::move(c));
      origin.push_back(more.file);
    }
    if (more.uff_ordinate_type != out.uff_ordinate_type) out.uff_ordinate_type = 0;
  }
  return out;
}

}  // namespace

std::optional<DataFormat> data_format_of(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".csv") return DataFormat::Csv;
  if (ext == ".uff" || ext == ".unv") return DataFormat::Uff;
  return std::nullopt;
}

std::vector<UffMapping> own_mappings(const std::vector<std::string>& paths) {
  std::vector<UffMapping> out;
  for (const std::string& path : paths)
    if (path != "-" && read_as_uff(path) && std::filesystem::exists(path + ".map"))
      out.push_back(read_uff_mapping(path + ".map"));
  return out;
}

std::vector<std::string> carried_comments(const std::vector<std::string>& paths) {
  std::vector<std::string> first;
  std::string first_path;
  for (const std::string& path : paths) {
    std::vector<std::string> lines;
    if (const std::optional<MeasurementTime> time = read_measurement_time(path)) lines.push_back("# time=" + time->text);
    for (const ConditionValue& c : read_operating_conditions(path))
      lines.push_back(fmt::format("# condition {}={}", c.name, c.value));  // the shortest text of the double
    if (lines.empty()) continue;
    if (first_path.empty()) {
      first = lines, first_path = path;
    } else if (lines != first) {
      throw DataError(path, 0, 0, "its `# time=` or `# condition` lines differ from those of " + first_path +
                                      ": one file holds one measurement, convert them one by one");
    }
  }
  return first;
}

DataSet read_for_writing(const std::vector<std::string>& paths, const std::string& model_path,
                         const std::vector<std::string>& sets, std::vector<UffMapping>& mappings) {
  std::vector<DataSet> data;
  if (!model_path.empty()) {
    symbolic::DeriveOptions derive;
    derive.set = parse_set_options(sets);
    const ir::ModelIr model = frontend::parse_file(model_path);
    const auto evaluator = evaluator::make_evaluator(model, derive);
    data = load_data(paths, evaluator->info(), model, derive.set);
  } else {
    for (const std::string& path : paths) data.push_back(read_data_file(path));
  }
  for (UffMapping& m : own_mappings(paths)) mappings.push_back(std::move(m));
  std::vector<FrfData> frfs;
  for (DataSet& d : data) {
    if (!d.is_frf()) {
      if (data.size() > 1)
        throw DataError(d.file(), 0, 0, "a time record is converted alone: give it as the only data file");
      return std::move(d);
    }
    frfs.push_back(std::get<FrfData>(std::move(d.content)));
  }
  return DataSet(joined(std::move(frfs)));
}

DataTexts data_texts(const DataSet& data, const DataWriteRequest& request) {
  std::ostringstream text;
  if (request.format == DataFormat::Csv) {
    for (const std::string& line : request.comments) text << line << "\n";
    if (data.is_frf())
      write_frf_csv(text, std::get<FrfData>(data.content));
    else
      write_time_record_csv(text, std::get<TimeRecord>(data.content));
    return {text.str(), ""};
  }
  if (!data.is_frf())
    throw DataError(data.file(), 0, 0,
                    "a time record is written as CSV only (mbgen reads UFF time responses, it does not write them): "
                    "name a .csv output");
  const FrfData& frf = std::get<FrfData>(data.content);
  UffPointRules rules;
  rules.mappings = request.mappings;
  std::optional<SensorGeometry> geometry;
  if (!request.model_path.empty()) {
    const ir::ModelIr model = frontend::parse_file(request.model_path);
    std::map<std::string, double> values;
    for (const auto& [name, text] : parse_set_options(request.sets)) values[name] = std::stod(text);
    rules.model_outputs = &geometry.emplace(sensor_geometry(model, values));
    for (const ir::Input& in : model.inputs) rules.model_inputs.push_back(in.name);
    for (const ir::Output& out : model.outputs) rules.output_types[out.name] = specific_data_type(out.kind);
    rules.model_first = true;
  }
  if (request.quantity != "auto") {
    const int type = request.quantity == "receptance" ? 8 : request.quantity == "mobility" ? 11 : 12;
    for (const FrfChannel& c : frf.channels) rules.output_types[c.output] = type;
  }
  const UffText uff = frf_uff58_text(frf, rules, request.title);
  return {uff.data, uff.mapping};
}

}  // namespace mbgen::cli
