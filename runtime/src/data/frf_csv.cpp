// Reading CSV FRFs: columns `OUTPUT/INPUT.re`, `.im` and optional `.coh` after `f_hz`.
#include <fstream>
#include <iostream>

#include "csv_table.hpp"
#include "mbgen/data/csv.hpp"
#include "mbgen/data/data_error.hpp"

namespace mbgen {

using namespace data_detail;

namespace {

struct ChannelColumns {
  std::string output, input;
  int re = -1, im = -1, coh = -1;  // column indices
};

Eigen::VectorXd column_vector(const std::vector<double>& c) {
  return Eigen::Map<const Eigen::VectorXd>(c.data(), static_cast<Eigen::Index>(c.size()));
}

std::vector<ChannelColumns> channel_columns(const CsvTable& table, const std::optional<ChannelNames>& known) {
  std::vector<ChannelColumns> channels;
  for (std::size_t c = 1; c < table.header.size(); ++c) {
    const std::string& name = table.header[c];
    const int column = static_cast<int>(c) + 1;
    const auto dot = name.rfind('.');
    const auto slash = name.find('/');
    const std::string suffix = dot == std::string::npos ? "" : name.substr(dot + 1);
    if (dot == std::string::npos || slash == std::string::npos || slash > dot ||
        (suffix != "re" && suffix != "im" && suffix != "coh"))
      throw DataError(table.file, table.header_line, column,
                      "column '" + name + "' is not of the form OUTPUT/INPUT.re, .im or .coh");
    const std::string output = name.substr(0, slash), input = name.substr(slash + 1, dot - slash - 1);
    if (output.empty() || input.empty())
      throw DataError(table.file, table.header_line, column, "column '" + name + "' lacks an output or input name");
    if (known && !known->is_output(output))
      throw DataError(table.file, table.header_line, column,
                      "column '" + name + "': '" + output + "' is not a model output (" + known->describe() + ")");
    if (known && !known->is_input(input))
      throw DataError(table.file, table.header_line, column,
                      "column '" + name + "': '" + input + "' is not a model input (" + known->describe() + ")");
    ChannelColumns* channel = nullptr;
    for (auto& ch : channels)
      if (ch.output == output && ch.input == input) channel = &ch;
    if (!channel) {
      channels.push_back(ChannelColumns{output, input});
      channel = &channels.back();
    }
    int& slot = suffix == "re" ? channel->re : suffix == "im" ? channel->im : channel->coh;
    slot = static_cast<int>(c);  // duplicates were rejected with the header
  }
  for (const auto& ch : channels) {
    const std::string pair = ch.output + "/" + ch.input;
    const int some = ch.re >= 0 ? ch.re : ch.im >= 0 ? ch.im : ch.coh;
    if (ch.re < 0 || ch.im < 0)
      throw DataError(table.file, table.header_line, some + 1,
                      "missing column '" + pair + (ch.re < 0 ? ".re" : ".im") + "': each FRF needs both " + pair +
                          ".re and " + pair + ".im");
  }
  return channels;
}

}  // namespace

FrfData read_frf_csv(std::istream& in, const std::string& file_name, const std::optional<ChannelNames>& known) {
  CsvTable table = read_csv_table(in, file_name);
  if (table.header[0] != "f_hz")
    throw DataError(file_name, table.header_line, 1,
                    "the first column of an FRF file must be 'f_hz', found '" + table.header[0] + "'" +
                        (table.header[0] == "t" ? " (this is a time record)" : ""));
  if (table.config.hold)
    throw DataError(file_name, table.config.hold_line, 0, "'# hold=' applies to time records only, not to FRFs");
  if (table.header.size() < 2) throw DataError(file_name, table.header_line, 0, "no FRF columns after 'f_hz'");
  const auto channels = channel_columns(table, known);

  const auto& f = table.columns[0];
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (f[k] < 0)
      throw DataError(file_name, table.row_lines[k], 1, "negative frequency " + format_double(f[k]) + " Hz");
    if (k > 0 && !(f[k] > f[k - 1]))
      throw DataError(file_name, table.row_lines[k], 1,
                      "frequencies must be strictly increasing: " + format_double(f[k]) + " after " +
                          format_double(f[k - 1]));
  }

  FrfData frf;
  frf.file = file_name;
  frf.set = std::move(table.config.set);
  frf.f_hz = column_vector(f);
  for (const auto& ch : channels) {
    FrfChannel out{ch.output, ch.input, Eigen::VectorXcd(frf.f_hz.size()), std::nullopt};
    for (std::size_t k = 0; k < f.size(); ++k)
      out.values[static_cast<Eigen::Index>(k)] = {table.columns[static_cast<std::size_t>(ch.re)][k],
                                                  table.columns[static_cast<std::size_t>(ch.im)][k]};
    if (ch.coh >= 0) {
      const auto& coh = table.columns[static_cast<std::size_t>(ch.coh)];
      for (std::size_t k = 0; k < coh.size(); ++k)
        if (coh[k] < 0 || coh[k] > 1)
          throw DataError(file_name, table.row_lines[k], ch.coh + 1,
                          "coherence " + format_double(coh[k]) + " in column '" +
                              table.header[static_cast<std::size_t>(ch.coh)] + "' is outside [0, 1]");
      out.coherence = column_vector(coh);
    }
    frf.channels.push_back(std::move(out));
  }
  return frf;
}

FrfData read_frf_csv(const std::string& path, const std::optional<ChannelNames>& known) {
  if (path == "-") return read_frf_csv(std::cin, path, known);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path, 0, 0, "cannot open file");
  return read_frf_csv(in, path, known);
}

}  // namespace mbgen
