#include "diagnosis/engine/prior_peaks.hpp"

#include <algorithm>
#include <cmath>

#include <mbgen/residuals/channel_residuals.hpp>

#include "diagnosis/engine/thresholds.hpp"

namespace mbgen::diagnosis {

std::string output_of(const std::string& channel) { return channel.substr(0, channel.find('/')); }

void add_distinct(std::vector<double>& peaks, double f) {
  if (std::none_of(peaks.begin(), peaks.end(), [&](double g) { return std::abs(f - g) <= thresholds::kSamePeak * f; }))
    peaks.push_back(f);
}

std::vector<double> strongest_first(std::vector<std::pair<double, double>> found) {
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<double> peaks;
  for (const auto& [strength, f] : found) add_distinct(peaks, f);
  return peaks;
}

std::set<std::string> outputs_missed_alone(const std::vector<ChannelResidual>& channels) {
  std::map<std::string, std::pair<double, long>> sums;  // output -> (sum of z, lines)
  for (const ChannelResidual& c : channels)
    for (Eigen::Index k = 0; k < c.measured.size(); ++k) {
      auto& s = sums[output_of(c.channel)];
      s.first += normalized_residual(c.measured[k], c.model[k], c.sigma[k]);
      ++s.second;
    }
  std::map<std::string, double> excess;
  for (const auto& [output, s] : sums)
    if (s.second > 0) excess[output] = s.first / static_cast<double>(s.second) - 1.0;
  std::set<std::string> out;
  for (const auto& [output, e] : excess) {
    bool alone = e > thresholds::kSensorAloneExcess;
    for (const auto& [other, f] : excess)
      if (other != output && !(e >= thresholds::kSensorAloneRatio * f)) alone = false;
    if (alone) out.insert(output);
  }
  return out;
}

PriorPeaks prior_peaks(const Model& evaluator, const std::vector<DataSet>& data, const FrfWeighting& weighting) {
  PriorPeaks out;
  std::vector<std::pair<double, double>> found;  // (magnitude relative to the channel's RMS, f)
  struct OutputPeak {
    double height;  // relative to the channel's RMS
    double prominence_db;
    double f;
  };
  std::map<std::string, std::vector<OutputPeak>> by_output;
  out.channels = channel_residuals(evaluator, data, evaluator.info().default_values(), weighting);
  for (const ChannelResidual& c : out.channels) {
    if (c.measured.size() == 0) continue;  // no line stands out of the noise (a few lines only): nothing to find
    const std::vector<int> model_peaks = magnitude_peaks(c.model);
    const double rms = std::sqrt(c.measured.cwiseAbs2().mean());
    const auto unexplained = [&](double f) {
      return std::none_of(model_peaks.begin(), model_peaks.end(), [&](int m) {
        return std::abs(c.f_hz[static_cast<std::size_t>(m)] - f) <= thresholds::kPriorPeakMatch * f;
      });
    };
    // One scan for both lists: the 6 dB peaks are among the 3 dB ones.
    for (int i = 1; i + 1 < static_cast<int>(c.measured.size()); ++i) {
      const double prominence = peak_prominence_db(c.measured, i);
      const double f = c.f_hz[static_cast<std::size_t>(i)];
      if (prominence < thresholds::kPeakProminenceDb || !unexplained(f)) continue;
      // The rise must stand out of the noise too (4 standard deviations): in data near the noise level, noise
      // alone makes wiggles of several dB.
      const double magnitude = std::abs(c.measured[i]);
      const double rise = magnitude * (1.0 - std::pow(10.0, -prominence / 20.0));
      if (rise < thresholds::kPeakNoiseSigmas * c.sigma[i]) continue;
      const double height = std::abs(c.measured[i]) / rms;
      if (prominence >= thresholds::kStrongPeakProminenceDb) found.emplace_back(height, f);
      by_output[output_of(c.channel)].push_back({height, prominence, f});
    }
  }
  for (const auto& entry : by_output) {
    const std::string& output = entry.first;  // a named variable, not a structured binding: lambdas capture it
    std::vector<std::pair<double, double>> own, shared;  // (prominence, f) and (height, f)
    for (const OutputPeak& peak : entry.second) {
      const bool elsewhere = std::any_of(by_output.begin(), by_output.end(), [&](const auto& other) {
        return other.first != output && std::any_of(other.second.begin(), other.second.end(), [&](const OutputPeak& q) {
                 return std::abs(q.f - peak.f) <= thresholds::kSamePeak * peak.f;
               });
      });
      if (elsewhere)
        shared.emplace_back(peak.height, peak.f);
      else
        own.emplace_back(peak.prominence_db, peak.f);
    }
    std::vector<double> peaks = strongest_first(own);
    for (double f : strongest_first(shared)) add_distinct(peaks, f);
    out.output_peak_hz[output] = peaks;
  }
  out.peak_hz = strongest_first(found);
  return out;
}

}  // namespace mbgen::diagnosis
