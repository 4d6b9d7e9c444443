// The FRFs of one or more files on one frequency axis, cut to the band.
#include "mbgen/data/data_error.hpp"
#include "mbgen/data/data_set.hpp"
#include "mbgen/modal_identification/modal_identification.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace mbgen {

namespace {

std::string hz(double f) {
  std::ostringstream s;
  s << std::setprecision(10) << f;
  return s.str();
}

int index_of(std::vector<std::string>& names, const std::string& n) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == n) return static_cast<int>(i);
  names.push_back(n);
  return static_cast<int>(names.size() - 1);
}

// The indices of the lines of `frf` inside the band, f > 0.
std::vector<Eigen::Index> band_lines(const FrfData& frf, const FrequencyBand& band) {
  std::vector<Eigen::Index> lines;
  for (Eigen::Index k = 0; k < frf.f_hz.size(); ++k) {
    const double f = frf.f_hz[k];
    if (f > 0 && f >= band.lo_hz && f <= band.hi_hz) lines.push_back(k);
  }
  return lines;
}

}  // namespace

const char* frf_quantity_name(FrfQuantity q) {
  switch (q) {
    case FrfQuantity::Receptance:
      return "receptance";
    case FrfQuantity::Mobility:
      return "mobility";
    case FrfQuantity::Accelerance:
      return "accelerance";
    case FrfQuantity::Unknown:
      break;
  }
  return "unknown";
}

int frf_quantity_power(FrfQuantity q) {
  switch (q) {
    case FrfQuantity::Mobility:
      return 1;
    case FrfQuantity::Accelerance:
      return 2;
    default:
      return 0;
  }
}

namespace {
FrfQuantity quantity_of_ordinate_type(int type) {
  return type == 8 ? FrfQuantity::Receptance : type == 11 ? FrfQuantity::Mobility
         : type == 12 ? FrfQuantity::Accelerance : FrfQuantity::Unknown;
}
}  // namespace

FrfQuantity uff_frf_quantity(const std::vector<Uff58Record>& records) {
  FrfQuantity q = FrfQuantity::Unknown;
  bool first = true;
  for (const Uff58Record& r : records) {
    if (r.function_type != 4) continue;
    const FrfQuantity here = quantity_of_ordinate_type(r.ordinate_type);
    if (!first && here != q) return FrfQuantity::Unknown;
    q = here;
    first = false;
  }
  return q;
}

FrfQuantity uff_frf_quantity(const FrfData& frf) { return quantity_of_ordinate_type(frf.uff_ordinate_type); }

ModalData modal_data(const std::vector<FrfData>& files, const FrequencyBand& band, FrfQuantity quantity) {
  if (files.empty()) throw DataError("modal analysis: no FRF data given");
  ModalData out;
  out.quantity = quantity;
  std::vector<Eigen::Index> first_lines;
  std::vector<const Eigen::VectorXcd*> columns;
  for (std::size_t d = 0; d < files.size(); ++d) {
    const FrfData& frf = files[d];
    out.files.push_back(frf.file);
    if (frf.channels.empty()) throw DataError(frf.file, 0, 0, "no FRF channels");
    const std::vector<Eigen::Index> lines = band_lines(frf, band);
    if (static_cast<int>(lines.size()) < kMinModalLines)
      throw DataError(frf.file, 0, 0,
                      "the band " + hz(band.lo_hz) + ".." + hz(band.hi_hz) + " Hz holds " +
                          std::to_string(lines.size()) + " lines above 0 Hz; modal analysis needs at least " +
                          std::to_string(kMinModalLines));
    if (d == 0) {
      out.f_hz.resize(static_cast<Eigen::Index>(lines.size()));
      for (std::size_t k = 0; k < lines.size(); ++k) out.f_hz[static_cast<Eigen::Index>(k)] = frf.f_hz[lines[k]];
      first_lines = lines;
    } else {
      bool same = lines.size() == first_lines.size();
      for (std::size_t k = 0; same && k < lines.size(); ++k)
        same = frf.f_hz[lines[k]] == out.f_hz[static_cast<Eigen::Index>(k)];
      if (!same)
        throw DataError(frf.file, 0, 0,
                        "its frequencies in the band differ from those of " + files.front().file +
                            " (modal analysis needs every channel on the same lines)");
    }
    for (const FrfChannel& ch : frf.channels) {
      ModalData::Channel c;
      c.output = index_of(out.outputs, ch.output);
      c.input = index_of(out.inputs, ch.input);
      c.name = ch.output + "/" + ch.input;
      for (const ModalData::Channel& other : out.channels)
        if (other.name == c.name) throw DataError(frf.file, 0, 0, "channel " + c.name + " is given twice");
      out.channels.push_back(c);
      columns.push_back(&ch.values);
    }
    for (const Eigen::Index k : lines)
      for (const FrfChannel& ch : frf.channels)
        if (!std::isfinite(ch.values[k].real()) || !std::isfinite(ch.values[k].imag()))
          throw DataError(frf.file, 0, 0,
                          "channel " + ch.output + "/" + ch.input + " is not finite at " + hz(frf.f_hz[k]) + " Hz");
    // A channel zero in the band, or too small to square, has no modes to find, and its relative error came out
    // as 0 (a perfect fit) with exit status 0.
    for (const FrfChannel& ch : frf.channels) {
      double peak = 0;
      for (const Eigen::Index k : lines) peak = std::max(peak, std::abs(ch.values[k]));
      const std::string name = "channel " + ch.output + "/" + ch.input;
      if (peak == 0) throw DataError(frf.file, 0, 0, name + " is zero at every line in the band: it has no modes");
      if (peak < kMinSignalMagnitude)
        throw DataError(frf.file, 0, 0,
                        name + " is too small to analyse: its largest magnitude in the band, " + hz(peak) +
                            ", is below 1e-150, where squares underflow a double; give the data in smaller units");
    }
  }
  // Same lines in every file: the first file's line indices hold for all only if the axes agree entirely, so
  // each column is gathered with its own file's indices.
  out.H.resize(out.f_hz.size(), static_cast<Eigen::Index>(columns.size()));
  std::size_t c = 0;
  for (const FrfData& frf : files) {
    const std::vector<Eigen::Index> lines = band_lines(frf, band);
    for (std::size_t ch = 0; ch < frf.channels.size(); ++ch, ++c)
      for (std::size_t k = 0; k < lines.size(); ++k)
        out.H(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) = (*columns[c])[lines[k]];
  }
  return out;
}

}  // namespace mbgen
