// prior_peaks -- where the data show resonances the model lacks, judged before any fit: the measured FRFs' peaks
// against the model at its prior values, overall and per output, and the outputs the model misses more than all
// others. They steer where candidates place new modes and which outputs a sensor's own dynamics may explain.
#pragma once

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <mbgen/residuals/residual_analysis.hpp>
#include <mbgen/estimation/fit.hpp>

namespace mbgen::diagnosis {

struct PriorPeaks {
  // Peaks of the measured FRFs that no peak of the model at its prior values accounts for (none within 8 %),
  // strongest first. A fit can hide a missing mode by bending other parameters (a soft mount standing in for a
  // compliant base), so the fitted residual alone may not point at it; the data's own peaks against the prior
  // model do.
  std::vector<double> peak_hz;
  // The same per output, down to a lower prominence (3 dB, not 6: a sensor's mounting resonance is damped, 5 % and
  // more, and near 1 kHz the spindle's xs_front rises less than 5 dB at it), the output's own peaks first. A peak
  // that no other output shows is what a sensor's own resonance looks like; a structural mode shows on every output
  // that moves with it. The own peaks go by prominence, not height: a displacement FRF falls with frequency, so
  // height would favour a low wiggle over a clear peak at 1 kHz.
  std::map<std::string, std::vector<double>> output_peak_hz;
  // The data against the model at its prior values.
  std::vector<ChannelResidual> channels;
};

PriorPeaks prior_peaks(const Model& evaluator, const std::vector<DataSet>& data, const FrfWeighting& weighting);

// The output of channel "OUTPUT/INPUT".
std::string output_of(const std::string& channel);

// Appends f to `peaks` unless one already there is within 2 % of it (the same peak, seen again).
void add_distinct(std::vector<double>& peaks, double f);

// Frequencies of (strength, f) pairs, strongest first, those within 2 % of a stronger one left out.
std::vector<double> strongest_first(std::vector<std::pair<double, double>> found);

// The outputs the model misses more than all others: mean excess over the noise (mean normalized residual minus 1)
// above 0.5 and at least twice every other output's.
std::set<std::string> outputs_missed_alone(const std::vector<ChannelResidual>& channels);

}  // namespace mbgen::diagnosis
