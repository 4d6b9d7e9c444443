#include "mbgen/chain_scores.hpp"

#include <cmath>
#include <map>
#include <tuple>

namespace mbgen {

namespace {

std::string output_of(const std::string& channel) { return channel.substr(0, channel.find('/')); }
std::string input_of(const std::string& channel) {
  const std::size_t slash = channel.find('/');
  return slash == std::string::npos ? std::string() : channel.substr(slash + 1);
}

double weight(double sigma) { return 2.0 / std::max(sigma * sigma, 1e-300); }

}  // namespace

GainScore gain_score(const std::vector<ChannelResidual>& channels,
                     const std::function<bool(const std::string& channel)>& selected) {
  double u = 0, info = 0;
  GainScore out;
  for (const ChannelResidual& c : channels) {
    if (!selected(c.channel)) continue;
    for (Eigen::Index k = 0; k < c.measured.size(); ++k) {
      const double w = weight(c.sigma[k]);
      u += w * std::real(std::conj(c.model[k]) * (c.measured[k] - c.model[k]));
      info += w * std::norm(c.model[k]);
      ++out.lines;
    }
  }
  if (!(info > 0)) return out;
  out.factor = 1 + u / info;
  out.factor_std = 1 / std::sqrt(info);
  out.statistic = u * u / info;
  return out;
}

PassivityCheck driving_point_passivity(const Eigen::VectorXcd& h, const Eigen::VectorXd& sigma, int derivatives) {
  PassivityCheck out;
  long against = 0;
  for (Eigen::Index k = 0; k < h.size(); ++k) {
    // The part that is never negative for a passive driving point.
    const double power = derivatives == 1 ? h[k].real() : derivatives == 2 ? h[k].imag() : -h[k].imag();
    const double part_sigma = sigma[k] / std::sqrt(2.0);
    if (!(std::abs(power) > 3 * part_sigma)) continue;
    ++out.lines;
    against += power < 0 ? 1 : 0;
  }
  if (out.lines > 0) out.against_share = static_cast<double>(against) / static_cast<double>(out.lines);
  return out;
}

double swap_gain(const std::vector<ChannelResidual>& channels, const std::string& a, const std::string& b) {
  // (data set, input, output) -> the channel's lines by frequency
  using Key = std::tuple<std::string, std::string, std::string>;
  std::map<Key, const ChannelResidual*> by_key;
  for (const ChannelResidual& c : channels) by_key[{c.data_set, input_of(c.channel), output_of(c.channel)}] = &c;
  double gain = 0;
  for (const auto& [key, first] : by_key) {
    if (std::get<2>(key) != a) continue;
    const auto other = by_key.find({std::get<0>(key), std::get<1>(key), b});
    if (other == by_key.end()) continue;
    const ChannelResidual& second = *other->second;
    std::map<double, Eigen::Index> lines_of_second;
    for (std::size_t k = 0; k < second.f_hz.size(); ++k) lines_of_second[second.f_hz[k]] = static_cast<Eigen::Index>(k);
    for (std::size_t i = 0; i < first->f_hz.size(); ++i) {
      const auto line = lines_of_second.find(first->f_hz[i]);
      if (line == lines_of_second.end()) continue;
      const auto p = static_cast<Eigen::Index>(i), q = line->second;
      const double wa = weight(first->sigma[p]), wb = weight(second.sigma[q]);
      const double as_is = wa * std::norm(first->measured[p] - first->model[p]) +
                           wb * std::norm(second.measured[q] - second.model[q]);
      const double exchanged = wa * std::norm(second.measured[q] - first->model[p]) +
                               wb * std::norm(first->measured[p] - second.model[q]);
      gain += as_is - exchanged;
    }
  }
  return gain;
}

}  // namespace mbgen
