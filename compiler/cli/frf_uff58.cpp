#include "cli/frf_uff58.hpp"

#include <mbgen/data/data_error.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <set>
#include <sstream>

namespace mbgen::cli {

namespace {

std::string key_of(const UffPoint& p) { return uff_point_key(p.node, p.direction); }

// The data's own point for `name`: its text, or a mapping file's line.
std::optional<UffPoint> own_point(const std::string& name, const std::vector<UffMapping>& mappings) {
  UffPoint p;
  if (name.rfind("node", 0) == 0 && parse_uff_point_key(name.substr(4), p)) return p;
  for (const UffMapping& mapping : mappings)
    for (const auto& [key, mapped] : mapping.names)
      if (mapped == name && parse_uff_point_key(key, p)) return p;
  return std::nullopt;
}

std::optional<UffPoint> model_point(const std::string& name, bool output, const UffPointRules& rules) {
  if (output && rules.model_outputs) {
    const auto it = rules.model_outputs->outputs.find(name);
    if (it != rules.model_outputs->outputs.end()) return it->second;
  }
  if (!output) {
    const auto it = std::find(rules.model_inputs.begin(), rules.model_inputs.end(), name);
    if (it != rules.model_inputs.end()) return UffPoint{1001 + static_cast<int>(it - rules.model_inputs.begin()), 1};
  }
  return std::nullopt;
}

// Every output's and input's point (a name that is both gets one point, found as an output).
std::map<std::string, UffPoint> channel_points(const FrfData& data, const UffPointRules& rules) {
  std::vector<std::pair<std::string, bool>> names;  // (name, is output) in order of first appearance
  const auto note = [&](const std::string& name, bool output) {
    for (const auto& [seen, is_output] : names)
      if (seen == name) return;
    names.emplace_back(name, output);
  };
  for (const FrfChannel& c : data.channels) note(c.output, true);
  for (const FrfChannel& c : data.channels) note(c.input, false);

  std::map<std::string, UffPoint> points;
  std::map<std::string, std::string> taken;  // point key -> name
  const auto take = [&](const std::string& name, const UffPoint& p) {
    const auto [it, fresh] = taken.emplace(key_of(p), name);
    if (!fresh)
      throw DataError(data.file, 0, 0,
                      "the channels `" + it->second + "` and `" + name + "` would both be the UFF point " + key_of(p) +
                          ": give them distinct points in a mapping file beside the data (FILE.map, e.g. `" +
                          key_of(p) + " = " + it->second + "`)");
    points[name] = p;
  };
  for (const auto& [name, output] : names) {
    std::optional<UffPoint> p = rules.model_first ? model_point(name, output, rules) : own_point(name, rules.mappings);
    if (!p) p = rules.model_first ? own_point(name, rules.mappings) : model_point(name, output, rules);
    if (p) take(name, *p);
  }
  int next_output = 1, next_input = 1001;
  for (const auto& [name, output] : names) {
    if (points.count(name)) continue;
    int& next = output ? next_output : next_input;
    while (taken.count(uff_point_key(next, 1))) ++next;
    take(name, UffPoint{next++, 1});
  }
  return points;
}

// Whether the reader reproduces every line from record 7's minimum and increment (six significant digits each).
bool evenly_written(const Eigen::VectorXd& f, double& min, double& increment) {
  const Eigen::Index n = f.size();
  if (n < 2) return false;
  const auto as_written = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%13.5E", v);
    return std::strtod(text, nullptr);
  };
  min = as_written(f[0]);
  increment = as_written((f[n - 1] - f[0]) / static_cast<double>(n - 1));
  if (!(increment > 0)) return false;
  for (Eigen::Index k = 0; k < n; ++k)
    if (min + static_cast<double>(k) * increment != f[k]) return false;  // the reader's x_k, bit for bit
  return true;
}

void ordinate_axis(int type, Uff58Record& r) {
  r.ordinate_type = type;
  r.ordinate_label = type == 8 ? "displacement" : type == 11 ? "velocity" : type == 12 ? "acceleration" : "NONE";
  r.ordinate_units = type == 8 ? "m" : type == 11 ? "m/s" : type == 12 ? "m/s^2" : "NONE";
}

// The mapping file's line for a name, checked by the reader that will read it.
std::string mapping_line(const std::string& file, const std::string& name, const UffPoint& p) {
  const std::string line = key_of(p) + " = " + name + "\n";
  try {
    std::istringstream in(line);
    read_uff_mapping(in, "mapping");
  } catch (const DataError&) {
    throw DataError(file, 0, 0,
                    "the channel name `" + name + "` cannot stand in a UFF mapping file (letters, digits and _, "
                    "not starting with a digit): rename it in the data");
  }
  return line;
}

}  // namespace

int uff_specific_data_type(FrfQuantity q) {
  switch (q) {
    case FrfQuantity::Receptance: return 8;
    case FrfQuantity::Mobility: return 11;
    case FrfQuantity::Accelerance: return 12;
    case FrfQuantity::Unknown: break;
  }
  return 0;
}

UffText frf_uff58_text(const FrfData& data, const UffPointRules& rules, const std::string& title) {
  if (data.channels.empty() || data.f_hz.size() == 0)
    throw DataError(data.file, 0, 0, "no FRF to write");
  const std::map<std::string, UffPoint> points = channel_points(data, rules);

  UffText out;
  out.mapping = "# " + title + ": UFF points to channels\n";
  for (const auto& [name, value] : data.set) out.mapping += "set " + name + "=" + value.text + "\n";
  std::set<std::string> mapped;
  for (const FrfChannel& c : data.channels)
    for (const std::string& name : {c.output, c.input}) {
      const UffPoint& p = points.at(name);
      if (name != "node" + key_of(p) && mapped.insert(name).second) out.mapping += mapping_line(data.file, name, p);
    }

  double min = 0, increment = 0;
  const bool even = evenly_written(data.f_hz, min, increment);
  std::ostringstream text;
  for (const FrfChannel& c : data.channels) {
    const UffPoint &response = points.at(c.output), &reference = points.at(c.input);
    Uff58Record rec;
    rec.id = {title, c.output + "/" + c.input, "NONE", "NONE", "NONE"};
    rec.function_type = 4;
    rec.response_entity = rec.reference_entity = "mbgen";
    rec.response_node = response.node, rec.response_direction = response.direction;
    rec.reference_node = reference.node, rec.reference_direction = reference.direction;
    rec.ordinate_data_type = 6;
    rec.even_spacing = even;
    rec.abscissa_min = min, rec.abscissa_increment = increment;
    rec.abscissa_type = 18, rec.abscissa_label = "Frequency", rec.abscissa_units = "Hz";
    const auto type = rules.output_types.find(c.output);
    ordinate_axis(type != rules.output_types.end() ? type->second : data.uff_ordinate_type, rec);
    rec.ordinate_denominator_type = 13, rec.ordinate_denominator_label = "force", rec.ordinate_denominator_units = "N";
    rec.x = data.f_hz;
    rec.y = c.values;
    write_uff58(text, rec);
    if (!c.coherence) continue;
    rec.id[1] = c.output + "/" + c.input + " coherence";
    rec.function_type = 6;
    rec.ordinate_data_type = 4;
    rec.ordinate_type = 0, rec.ordinate_label = "coherence", rec.ordinate_units = "NONE";
    rec.ordinate_denominator_type = 0, rec.ordinate_denominator_label = "NONE", rec.ordinate_denominator_units = "NONE";
    rec.y = c.coherence->cast<std::complex<double>>();
    write_uff58(text, rec);
  }
  out.data = text.str();
  return out;
}

}  // namespace mbgen::cli
