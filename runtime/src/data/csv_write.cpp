// Writing CSV time records and FRFs in the formats the readers accept.
#include <ostream>

#include "mbgen/data/csv.hpp"
#include "mbgen/data/data_error.hpp"
#include "text_parsing.hpp"

namespace mbgen {

using data_detail::format_double;

namespace {
void write_set_lines(std::ostream& out, const SetMap& set) {
  for (const auto& [name, value] : set) out << "# set " << name << "=" << value.text << "\n";
}
}  // namespace

void write_time_record_csv(std::ostream& out, const TimeRecord& record) {
  write_set_lines(out, record.set);
  if (record.hold == HoldMode::None) out << "# hold=none\n";
  out << "t";
  for (const auto& s : record.signals) {
    if (s.values.size() != record.t.size())
      throw DataError(record.file, 0, 0, "signal '" + s.name + "' has " + std::to_string(s.values.size()) +
                                             " samples, the time column " + std::to_string(record.t.size()));
    out << "," << s.name;
  }
  out << "\n";
  for (Eigen::Index k = 0; k < record.t.size(); ++k) {
    out << format_double(record.t[k]);
    for (const auto& s : record.signals) out << "," << format_double(s.values[k]);
    out << "\n";
  }
}

void write_frf_csv(std::ostream& out, const FrfData& frf) {
  write_set_lines(out, frf.set);
  out << "f_hz";
  for (const auto& ch : frf.channels) {
    const std::string pair = ch.output + "/" + ch.input;
    if (ch.values.size() != frf.f_hz.size() || (ch.coherence && ch.coherence->size() != frf.f_hz.size()))
      throw DataError(frf.file, 0, 0, "FRF '" + pair + "' does not have one value per frequency");
    out << "," << pair << ".re," << pair << ".im";
    if (ch.coherence) out << "," << pair << ".coh";
  }
  out << "\n";
  for (Eigen::Index k = 0; k < frf.f_hz.size(); ++k) {
    out << format_double(frf.f_hz[k]);
    for (const auto& ch : frf.channels) {
      out << "," << format_double(ch.values[k].real()) << "," << format_double(ch.values[k].imag());
      if (ch.coherence) out << "," << format_double((*ch.coherence)[k]);
    }
    out << "\n";
  }
}

}  // namespace mbgen
