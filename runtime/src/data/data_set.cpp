// Reading any data file: dispatch on UFF name or content, else on the CSV header's first column.
#include "mbgen/data_set.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <streambuf>

#include "mbgen/csv.hpp"
#include "mbgen/data_error.hpp"
#include "text_parsing.hpp"

namespace mbgen {

using namespace data_detail;

namespace {

bool has_uff_extension(const std::string& name) {
  std::string ext = std::filesystem::path(name).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".uff" || ext == ".unv";
}

enum class Kind { Uff, Time, Frf };

// An input stream over bytes already in memory, without copying them (std::istringstream would).
class BytesBuffer : public std::streambuf {
 public:
  // A UTF-8 byte order mark (as some programs write before the first line) is left out.
  explicit BytesBuffer(std::string& bytes) {
    char* start = bytes.data() + (bytes.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0);
    setg(start, start, bytes.data() + bytes.size());
  }
};

// All of a stream's bytes, in one allocation of the right size where the stream can tell its size (a file).
std::string read_all(std::istream& in) {
  std::string bytes;
  const std::streampos start = in.tellg();
  if (start != std::streampos(-1) && in.seekg(0, std::ios::end)) {
    const std::streampos end = in.tellg();
    in.seekg(start);
    if (end != std::streampos(-1) && end >= start) {
      bytes.resize(static_cast<std::size_t>(end - start));
      in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      bytes.resize(static_cast<std::size_t>(in.gcount()));
      return bytes;
    }
  }
  in.clear();
  bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return bytes;
}

Kind detect(std::string& bytes, const std::string& file_name) {
  if (has_uff_extension(file_name)) return Kind::Uff;
  BytesBuffer buffer(bytes);
  std::istream in(&buffer);
  LineReader reader(in);
  std::string line;
  while (reader.next(line)) {
    const std::string_view text = trim(line);
    if (text.empty()) continue;
    if (text == "-1") return Kind::Uff;
    if (text.front() == '#') continue;
    const std::string_view first = split_fields(text).front();
    if (first == "t") return Kind::Time;
    if (first == "f_hz") return Kind::Frf;
    throw DataError(file_name, reader.line_number(), 1,
                    "cannot tell the kind of data: the header starts with '" + std::string(first) +
                        "', expected 't' (time record) or 'f_hz' (FRFs), or a UFF file (.uff, or '    -1' first)");
  }
  throw DataError(file_name, 0, 0, bytes.empty() ? "empty file" : "no header row (only comments)");
}

DataFile read_any(std::istream& in, const std::string& file_name, const std::optional<ChannelNames>& known,
                 const std::optional<UffMapping>& uff_mapping, const std::string& sidecar) {
  // Read everything first: standard input cannot be rewound after looking at the header.
  std::string bytes = read_all(in);
  BytesBuffer buffer(bytes);
  std::istream body(&buffer);
  switch (detect(bytes, file_name)) {
    case Kind::Time: return read_time_record_csv(body, file_name, known);
    case Kind::Frf: return read_frf_csv(body, file_name, known);
    case Kind::Uff: break;
  }
  const auto records = read_uff58(body, file_name);
  UffMapping mapping;
  if (uff_mapping)
    mapping = *uff_mapping;
  else if (!sidecar.empty() && std::filesystem::exists(sidecar))
    mapping = read_uff_mapping(sidecar);
  const auto set = uff_to_data_set(records, file_name, mapping, known);
  if (std::holds_alternative<TimeRecord>(set)) return std::get<TimeRecord>(set);
  return std::get<FrfData>(set);
}

}  // namespace

DataFile read_data(std::istream& in, const std::string& file_name, const std::optional<ChannelNames>& known,
                  const std::optional<UffMapping>& uff_mapping) {
  return read_any(in, file_name, known, uff_mapping, "");
}

DataFile read_data_file(const std::string& path, const std::optional<ChannelNames>& known,
                       const std::optional<UffMapping>& uff_mapping) {
  if (path == "-") return read_data(std::cin, path, known, uff_mapping);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw DataError(path, 0, 0, "is a directory, not a data file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path, 0, 0, "cannot open file");
  return read_any(in, path, known, uff_mapping, path + ".map");
}

DataFile read_data_file(const std::string& path, const std::vector<std::string>& known_inputs,
                       const std::vector<std::string>& known_outputs) {
  return read_data_file(path, ChannelNames{known_inputs, known_outputs});
}

const std::string& data_file(const DataFile& data) {
  return std::visit([](const auto& d) -> const std::string& { return d.file; }, data);
}

const SetMap& data_set_values(const DataFile& data) {
  return std::visit([](const auto& d) -> const SetMap& { return d.set; }, data);
}

}  // namespace mbgen
