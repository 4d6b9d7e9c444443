// From UFF 58 records to the project's data sets: point keys, mapping files, FRFs and time records.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>

#include "mbgen/data/data_error.hpp"
#include "mbgen/data/data_set.hpp"
#include "mbgen/data/uff.hpp"
#include "text_parsing.hpp"

namespace mbgen {

using namespace data_detail;

namespace {

const char* const kDirections[] = {"S", "+X", "+Y", "+Z", "+RX", "+RY", "+RZ"};

std::string function_type_name(int type) {
  switch (type) {
    case 0: return "general";
    case 1: return "time response";
    case 2: return "auto spectrum";
    case 3: return "cross spectrum";
    case 4: return "frequency response function";
    case 5: return "transmissibility";
    case 6: return "coherence";
    case 9: return "power spectral density";
    default: return "type " + std::to_string(type);
  }
}

// "NODE:DIR" back to numbers; false when the text is not a point key.
bool parse_point_key(std::string_view key, int& node, int& direction) {
  const auto colon = key.find(':');
  if (colon == std::string_view::npos) return false;
  const auto n = parse_number(trim(key.substr(0, colon)));
  if (!n || *n != std::floor(*n) || std::abs(*n) > 2e9) return false;
  const std::string_view dir = trim(key.substr(colon + 1));
  for (int d = -6; d <= 6; ++d)
    if (uff_direction_name(d) == dir) {
      node = static_cast<int>(*n);
      direction = d;
      return true;
    }
  return false;
}

bool same_abscissa(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return false;
  const double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return ((a - b).cwiseAbs().array() <= 1e-9 * scale).all();
}

std::string point_text(const UffMapping& m, int node, int dir) {
  return uff_point_key(node, dir) + " ('" + uff_channel_name(m, node, dir) + "')";
}

std::string mapping_hint(int node, int dir) {
  return "; name it in a mapping file with a line such as '" + uff_point_key(node, dir) + " = NAME'";
}

FrfData frf_from_records(const std::vector<const Uff58Record*>& frfs, const std::vector<const Uff58Record*>& cohs,
                         const std::string& file, const UffMapping& m, const std::optional<ChannelNames>& known) {
  FrfData data;
  data.file = file;
  data.set = m.set;
  const Uff58Record& first = *frfs.front();
  if (m.hold) throw DataError(file, 0, 0, "the mapping's 'hold=' applies to time records, this file holds FRFs");
  for (const Uff58Record* r : frfs) {
    if (r->abscissa_type == 17)
      throw DataError(file, r->line, 0, "UFF FRF record has a time abscissa (record 8 specific data type 17)");
    if (!same_abscissa(r->x, first.x))
      throw DataError(file, r->line, 0,
                      "UFF FRF record has other frequencies than the first one (line " + std::to_string(first.line) +
                          "): all FRFs of a file must share them");
    FrfChannel ch;
    ch.output = uff_channel_name(m, r->response_node, r->response_direction);
    ch.input = uff_channel_name(m, r->reference_node, r->reference_direction);
    if (known && !known->is_output(ch.output))
      throw DataError(file, r->line, 0,
                      "UFF FRF response point " + point_text(m, r->response_node, r->response_direction) +
                          " is not a model output (" + known->describe() + ")" +
                          mapping_hint(r->response_node, r->response_direction));
    if (known && !known->is_input(ch.input))
      throw DataError(file, r->line, 0,
                      "UFF FRF reference point " + point_text(m, r->reference_node, r->reference_direction) +
                          " is not a model input (" + known->describe() + ")" +
                          mapping_hint(r->reference_node, r->reference_direction));
    if (data.find(ch.output, ch.input))
      throw DataError(file, r->line, 0, "UFF file holds the FRF " + ch.output + "/" + ch.input + " twice");
    ch.values = r->y;
    data.channels.push_back(std::move(ch));
  }
  data.f_hz = first.x;
  data.uff_ordinate_type = first.ordinate_type;
  for (const Uff58Record* r : frfs)
    if (r->ordinate_type != first.ordinate_type) data.uff_ordinate_type = 0;
  for (Eigen::Index k = 0; k < data.f_hz.size(); ++k) {
    if (data.f_hz[k] < 0)
      throw DataError(file, first.line, 0, "UFF FRF record has a negative frequency " + format_double(data.f_hz[k]));
    if (k > 0 && !(data.f_hz[k] > data.f_hz[k - 1]))
      throw DataError(file, first.line, 0, "UFF FRF frequencies are not strictly increasing at point " +
                                               std::to_string(k + 1));
  }
  for (const Uff58Record* r : cohs) {
    const std::string out = uff_channel_name(m, r->response_node, r->response_direction);
    const std::string in = uff_channel_name(m, r->reference_node, r->reference_direction);
    auto it = std::find_if(data.channels.begin(), data.channels.end(),
                           [&](const FrfChannel& c) { return c.output == out && c.input == in; });
    if (it == data.channels.end())
      throw DataError(file, r->line, 0, "UFF coherence record " + out + "/" + in + " has no matching FRF record");
    if (!same_abscissa(r->x, first.x))
      throw DataError(file, r->line, 0, "UFF coherence record has other frequencies than the FRFs");
    if (it->coherence) throw DataError(file, r->line, 0, "UFF file holds the coherence " + out + "/" + in + " twice");
    Eigen::VectorXd coh = r->y.real();
    for (Eigen::Index k = 0; k < coh.size(); ++k)
      if (coh[k] < 0 || coh[k] > 1)
        throw DataError(file, r->line, 0, "UFF coherence " + format_double(coh[k]) + " at point " +
                                              std::to_string(k + 1) + " is outside [0, 1]");
    it->coherence = coh;
  }
  return data;
}

TimeRecord time_from_records(const std::vector<const Uff58Record*>& records, const std::string& file,
                             const UffMapping& m, const std::optional<ChannelNames>& known) {
  TimeRecord rec;
  rec.file = file;
  rec.set = m.set;
  rec.hold = m.hold.value_or(HoldMode::ZeroOrder);
  const Uff58Record& first = *records.front();
  for (const Uff58Record* r : records) {
    if (r->is_complex())
      throw DataError(file, r->line, 0, "UFF time response record has complex values; a time record needs real ones");
    if (!r->even_spacing)
      throw DataError(file, r->line, 0, "UFF time response record is unevenly sampled; time records must be uniform");
    if (r->points < 2) throw DataError(file, r->line, 0, "UFF time response record needs at least 2 samples");
    if (r->points != first.points || r->abscissa_min != first.abscissa_min ||
        r->abscissa_increment != first.abscissa_increment)
      throw DataError(file, r->line, 0,
                      "UFF time response record has another time axis than the first one (line " +
                          std::to_string(first.line) + "): all signals of a file must share it");
    Signal s{uff_channel_name(m, r->response_node, r->response_direction), r->y.real()};
    if (known && !known->is_input(s.name) && !known->is_output(s.name))
      throw DataError(file, r->line, 0,
                      "UFF time response point " + point_text(m, r->response_node, r->response_direction) +
                          " is neither a model input nor output (" + known->describe() + ")" +
                          mapping_hint(r->response_node, r->response_direction));
    if (rec.find(s.name)) throw DataError(file, r->line, 0, "UFF file holds the signal '" + s.name + "' twice");
    rec.signals.push_back(std::move(s));
  }
  rec.t = first.x;
  return rec;
}

}  // namespace

std::string uff_direction_name(int direction) {
  if (direction < -6 || direction > 6) throw DataError("UFF direction code " + std::to_string(direction) + " is not in -6..6");
  if (direction >= 0) return kDirections[direction];
  return "-" + std::string(kDirections[-direction]).substr(1);
}

std::string uff_point_key(int node, int direction) {
  return std::to_string(node) + ":" + uff_direction_name(direction);
}

std::string uff_channel_name(const UffMapping& mapping, int node, int direction) {
  const auto it = mapping.names.find(uff_point_key(node, direction));
  if (it != mapping.names.end()) return it->second;
  return "node" + uff_point_key(node, direction);
}

UffMapping read_uff_mapping(std::istream& in, const std::string& file_name) {
  UffMapping mapping;
  DataConfig config;
  LineReader reader(in, file_name);
  std::string line;
  while (reader.next(line)) {
    const int at = reader.line_number();
    const std::string_view text = trim(line);
    if (text.empty() || text.front() == '#') continue;
    if (parse_config_comment(text, file_name, at, config)) continue;
    const auto eq = text.find('=');
    const std::string_view key = trim(text.substr(0, eq));
    const std::string_view name = eq == std::string_view::npos ? std::string_view() : trim(text.substr(eq + 1));
    int node = 0, direction = 0;
    if (eq == std::string_view::npos || !parse_point_key(key, node, direction))
      throw DataError(file_name, at, 1,
                      "expected 'NODE:DIR = NAME' (DIR one of +X +Y +Z +RX +RY +RZ, -X ... -RZ, S), "
                      "'set NAME=VALUE' or 'hold=none', found '" + std::string(text) + "'");
    if (!is_identifier(name))
      throw DataError(file_name, at, static_cast<int>(line.find(std::string(name), line.find('=') + 1)) + 1,
                      "'" + std::string(name) + "' is not a channel name");
    const std::string canonical = uff_point_key(node, direction);
    if (mapping.names.count(canonical))
      throw DataError(file_name, at, 1, "point " + canonical + " is mapped twice");
    mapping.names[canonical] = std::string(name);
  }
  mapping.set = std::move(config.set);
  mapping.hold = config.hold;
  return mapping;
}

UffMapping read_uff_mapping(const std::string& path) {
  if (path == "-") return read_uff_mapping(std::cin, path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path, 0, 0, "cannot open file");
  return read_uff_mapping(in, path);
}

DataSet uff_to_data_set(const std::vector<Uff58Record>& records, const std::string& file_name,
                        const UffMapping& mapping, const std::optional<ChannelNames>& known) {
  std::vector<const Uff58Record*> time, frf, coherence;
  for (const auto& r : records) {
    if (r.function_type == 1)
      time.push_back(&r);
    else if (r.function_type == 4)
      frf.push_back(&r);
    else if (r.function_type == 6)
      coherence.push_back(&r);
    else
      throw DataError(file_name, r.line, 0,
                      "UFF function type " + std::to_string(r.function_type) + " (" +
                          function_type_name(r.function_type) +
                          ") is not supported: only 1 (time response), 4 (FRF) and 6 (coherence of an FRF)");
  }
  if (records.empty()) throw DataError(file_name, 0, 0, "no UFF dataset 58 or 58b in the file");
  if (!time.empty() && (!frf.empty() || !coherence.empty()))
    throw DataError(file_name, (frf.empty() ? coherence : frf).front()->line, 0,
                    "UFF file mixes time responses (first on line " + std::to_string(time.front()->line) +
                        ") with FRFs or coherences: one data set is either a time record or FRFs");
  if (!time.empty()) return time_from_records(time, file_name, mapping, known);
  if (frf.empty())
    throw DataError(file_name, coherence.front()->line, 0, "UFF file holds coherences but no FRF");
  return frf_from_records(frf, coherence, file_name, mapping, known);
}

}  // namespace mbgen
