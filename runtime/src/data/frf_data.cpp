#include "mbgen/data/frf_data.hpp"

#include <stdexcept>

namespace mbgen {

const FrfChannel* FrfData::find(const std::string& output, const std::string& input) const {
  for (const auto& c : channels)
    if (c.output == output && c.input == input) return &c;
  return nullptr;
}

FrfData within_band(const FrfData& data, double lo_hz, double hi_hz) {
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < data.f_hz.size(); ++k)
    if (data.f_hz[k] >= lo_hz && data.f_hz[k] <= hi_hz) kept.push_back(k);
  if (kept.empty())
    throw std::invalid_argument(data.file + ": no frequency line between " + std::to_string(lo_hz) + " and " +
                                std::to_string(hi_hz) + " Hz");
  const auto n = static_cast<Eigen::Index>(kept.size());
  FrfData out;
  out.file = data.file;
  out.set = data.set;
  out.uff_ordinate_type = data.uff_ordinate_type;
  out.f_hz.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) out.f_hz[i] = data.f_hz[kept[static_cast<std::size_t>(i)]];
  for (const FrfChannel& c : data.channels) {
    FrfChannel k = c;
    k.values.resize(n);
    if (c.coherence) k.coherence = Eigen::VectorXd(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      k.values[i] = c.values[kept[static_cast<std::size_t>(i)]];
      if (c.coherence) (*k.coherence)[i] = (*c.coherence)[kept[static_cast<std::size_t>(i)]];
    }
    out.channels.push_back(std::move(k));
  }
  return out;
}

}  // namespace mbgen
