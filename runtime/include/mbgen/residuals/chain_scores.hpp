// Cheap tests of the measurement chain against a model's current fit (docs/diagnosis.md, "The measurement chain
// first"): does a channel read a constant factor of what the model predicts (a sensor's calibration or polarity, a
// force transducer's), or do two outputs' data fit better exchanged (swapped cables)? Each is a score or likelihood
// ratio statistic at the model's current parameters, from the measured and model FRFs and the noise level that
// channel_residuals.hpp gives per judged line: milliseconds, no fit. The diagnosis fits a chain candidate only where
// its statistic says the data would support it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <mbgen/residuals/residual_analysis.hpp>

namespace mbgen {

struct GainScore {
  double factor = 1;      // least-squares factor g of the data against the model, the model's parameters held
  double factor_std = 0;  // its standard deviation from the noise alone
  double statistic = 0;   // the score statistic for g = 1: chi-square with one degree of freedom when g is 1
  long lines = 0;         // judged lines it is computed over
};

// Over the channels `selected` picks ("OUTPUT/INPUT" names). With chi^2(g) = sum 2|d - g m|^2 / sigma^2 (real and
// imaginary parts each carry half the complex noise variance), the score at g = 1 is U = sum 2 Re(conj(m)(d - m)) /
// sigma^2, the information I = sum 2|m|^2 / sigma^2, the statistic U^2 / I, the factor 1 + U / I, its std 1/sqrt(I).
GainScore gain_score(const std::vector<ChannelResidual>& channels,
                     const std::function<bool(const std::string& channel)>& selected);

// A driving point (an output at an input's point, along its direction) of a passive structure takes in power at every
// frequency: with e^{i w t}, Im H <= 0 for a receptance (`derivatives` 0: displacement over force), Re H >= 0 for a
// mobility (1), Im H >= 0 for an accelerance (2). Over the lines where that part of H stands three standard
// deviations out of the noise (`sigma`, the complex value's), the share with the sign a passive structure cannot
// have: near 1 when the force or the sensor is recorded with the wrong sign. No model is needed.
struct PassivityCheck {
  long lines = 0;             // lines where the part stands out of the noise
  double against_share = 0;   // the share of them with the impossible sign
};
PassivityCheck driving_point_passivity(const Eigen::VectorXcd& h, const Eigen::VectorXd& sigma, int derivatives);

// How much chi^2 (as above) falls when outputs `a` and `b` exchange their data, the model's parameters held: over
// the lines both judge, per input and data set. Negative when the data fit better as they are; 0 without common
// lines.
double swap_gain(const std::vector<ChannelResidual>& channels, const std::string& a, const std::string& b);

// How much lower chi^2 (as above) is, each with its least-squares real factor, when output `output`'s model FRFs are
// multiplied by (i w)^derivatives than as they are, the model's parameters held: positive when the output's data
// are another form of its quantity (a mobility, derivatives 1, or an accelerance, 2, where the model has a
// receptance; -1, -2 the other way). 0 without lines.
double form_gain(const std::vector<ChannelResidual>& channels, const std::string& output, int derivatives);

// The least-squares slope of log10 |measured / model| against log10 f over output `output`'s lines: near k where the
// data are (i w)^k times the model's form. Resonances the model places elsewhere make spikes about the line, not a
// trend, so the slope shows a form where chi^2 (form_gain) at a misplaced model cannot. NaN without lines.
double magnitude_slope(const std::vector<ChannelResidual>& channels, const std::string& output);

}  // namespace mbgen
