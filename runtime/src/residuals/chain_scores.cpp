#include "mbgen/residuals/chain_scores.hpp"
#include "numerics/constants.hpp"

#include <cmath>
#include <limits>
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

double form_gain(const std::vector<ChannelResidual>& channels, const std::string& output, int derivatives) {
  // min over g of sum w |d - g m|^2 = sum w |d|^2 - U^2 / I with U = sum w Re(conj(m) d), I = sum w |m|^2.
  double u_as_is = 0, i_as_is = 0, u_form = 0, i_form = 0;
  for (const ChannelResidual& c : channels) {
    if (output_of(c.channel) != output) continue;
    for (Eigen::Index k = 0; k < c.measured.size(); ++k) {
      const double w = weight(c.sigma[k]);
      const std::complex<double> iw(0, numerics::kTwoPi * c.f_hz[static_cast<std::size_t>(k)]);
      const std::complex<double> m = c.model[k], mf = m * std::pow(iw, derivatives);
      u_as_is += w * std::real(std::conj(m) * c.measured[k]);
      i_as_is += w * std::norm(m);
      u_form += w * std::real(std::conj(mf) * c.measured[k]);
      i_form += w * std::norm(mf);
    }
  }
  if (!(i_as_is > 0) || !(i_form > 0)) return 0;
  return u_form * u_form / i_form - u_as_is * u_as_is / i_as_is;
}

double magnitude_slope(const std::vector<ChannelResidual>& channels, const std::string& output) {
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const ChannelResidual& c : channels) {
    if (output_of(c.channel) != output) continue;
    for (Eigen::Index k = 0; k < c.measured.size(); ++k) {
      const double f = c.f_hz[static_cast<std::size_t>(k)], d = std::abs(c.measured[k]), m = std::abs(c.model[k]);
      if (!(f > 0) || !(d > 0) || !(m > 0)) continue;
      const double x = std::log10(f), y = std::log10(d / m);
      sw += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
  }
  const double den = sw * sxx - sx * sx;
  if (sw < 3 || !(den > 0)) return std::numeric_limits<double>::quiet_NaN();
  return (sw * sxy - sx * sy) / den;
}

}  // namespace mbgen
