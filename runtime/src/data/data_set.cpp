// Reading any data file: dispatch on UFF name or content, else on the CSV header's first column.
#include "mbgen/data/data_set.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <streambuf>
#include <string>

#include "mbgen/data/csv.hpp"
#include "mbgen/data/data_error.hpp"
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

// A stream that can go back to its start only until release(): it keeps what it reads until then. The kind of data
// is told from the first lines, which are then read again by the parser; standard input cannot be rewound, and was
// read whole for this (`--data -` from /dev/zero grew one string until the memory ran out). What is kept is the
// lines looked at (each at most kMaxLineBytes) and one chunk.
class RewindableBuffer : public std::streambuf {
 public:
  explicit RewindableBuffer(std::streambuf& source) : source_(source) { setg(kept_.data(), kept_.data(), kept_.data()); }
  // From here on nothing more is kept: the rest of what was kept is read, then the source in chunks.
  void release() { keeping_ = false; }

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    if (keeping_) {
      const std::size_t at = kept_.size();
      kept_.resize(at + sizeof chunk_);
      const auto got = static_cast<std::size_t>(source_.sgetn(kept_.data() + at, sizeof chunk_));
      kept_.resize(at + got);
      setg(kept_.data(), kept_.data() + at, kept_.data() + kept_.size());
    } else {
      if (!kept_.empty()) std::string().swap(kept_);
      const auto got = static_cast<std::size_t>(source_.sgetn(chunk_, sizeof chunk_));
      setg(chunk_, chunk_, chunk_ + got);
    }
    return gptr() < egptr() ? traits_type::to_int_type(*gptr()) : traits_type::eof();
  }
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode which) override {
    if (!keeping_ || dir == std::ios_base::end) return pos_type(off_type(-1));
    const off_type base = dir == std::ios_base::beg ? 0 : gptr() - eback();
    return seekpos(pos_type(base + off), which);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode) override {
    const auto at = off_type(pos);
    if (!keeping_ || at < 0 || at > static_cast<off_type>(kept_.size())) return pos_type(off_type(-1));
    setg(kept_.data(), kept_.data() + at, kept_.data() + kept_.size());
    return pos;
  }

 private:
  std::streambuf& source_;
  std::string kept_;
  bool keeping_ = true;
  char chunk_[1 << 16];
};

// Skips a UTF-8 byte order mark (as some programs write before the first line) at the stream's position.
void skip_byte_order_mark(std::istream& in) {
  const std::streampos start = in.tellg();
  char mark[3] = {};
  if (in.read(mark, 3) && std::string_view(mark, 3) == "\xEF\xBB\xBF") return;
  in.clear();
  in.seekg(start);
}

// The kind of data from the name and the first lines, read from the stream's position.
Kind detect(std::istream& in, const std::string& file_name) {
  if (has_uff_extension(file_name)) return Kind::Uff;
  LineReader reader(in, file_name);
  std::string line;
  bool any = false;
  while (reader.next(line)) {
    any = true;
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
  throw DataError(file_name, 0, 0, any ? "no header row (only comments)" : "empty file");
}

DataSet parse(Kind kind, std::istream& body, const std::string& file_name, const std::optional<ChannelNames>& known,
               const std::optional<UffMapping>& uff_mapping, const std::string& sidecar) {
  switch (kind) {
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
  return uff_to_data_set(records, file_name, mapping, known);
}

DataSet read_any(std::istream& in, const std::string& file_name, const std::optional<ChannelNames>& known,
                 const std::optional<UffMapping>& uff_mapping, const std::string& sidecar) {
  // Any input, a file or standard input, is parsed from the stream itself after a look at its first lines, and so
  // never held as text beside its numbers (docs/limits.md, "Memory of a time record").
  RewindableBuffer buffer(*in.rdbuf());
  std::istream text(&buffer);
  skip_byte_order_mark(text);
  const std::streampos body = text.tellg();
  const Kind kind = detect(text, file_name);
  text.clear();
  text.seekg(body);
  buffer.release();
  return parse(kind, text, file_name, known, uff_mapping, sidecar);
}

}  // namespace

DataSet read_data(std::istream& in, const std::string& file_name, const std::optional<ChannelNames>& known,
                  const std::optional<UffMapping>& uff_mapping) {
  return read_any(in, file_name, known, uff_mapping, "");
}

DataSet read_data_file(const std::string& path, const std::optional<ChannelNames>& known,
                       const std::optional<UffMapping>& uff_mapping) {
  if (path == "-") return read_data(std::cin, path, known, uff_mapping);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw DataError(path, 0, 0, "is a directory, not a data file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path, 0, 0, "cannot open file");
  return read_any(in, path, known, uff_mapping, path + ".map");
}

DataSet read_data_file(const std::string& path, const std::vector<std::string>& known_inputs,
                       const std::vector<std::string>& known_outputs) {
  return read_data_file(path, ChannelNames{known_inputs, known_outputs});
}

const std::string& DataSet::file() const {
  return std::visit([](const auto& d) -> const std::string& { return d.file; }, content);
}

const SetMap& DataSet::set() const {
  return std::visit([](const auto& d) -> const SetMap& { return d.set; }, content);
}

}  // namespace mbgen
