// The noise level of a measured FRF, estimated from the data themselves.
//
// Judging a model's residual needs the measurement's standard deviation per line, on an absolute scale. Coherence
// gives its shape but not its scale (the variance of an H1 estimate is (1 - coh^2)/(n coh^2) |h|^2, the fit's weight,
// frf_sigma.hpp, which also says how the two relate; the number of averages n is rarely known), and many real FRF
// files have no coherence at all. The data carry their own noise:
// a measured FRF is a smooth response plus noise that changes from line to line. Fourth differences
//
//     d_k = h_{k-2} - 4 h_{k-1} + 6 h_k - 4 h_{k+1} + h_{k+2}
//
// cancel any cubic through five lines and keep the noise: for independent complex noise of variance s_j^2 per
// line, E|d_k|^2 = s_{k-2}^2 + 16 s_{k-1}^2 + 36 s_k^2 + 16 s_{k+1}^2 + s_{k+2}^2, and |d_k|^2 is exponentially
// distributed about that mean. Where a sharp resonance bends the response over a few lines its curvature adds to
// d_k; those lines stand far above the noise's exponential tail and are left out. (Not second differences: around
// a resonance ten lines wide their curvature term is ten times larger, and a fit takes it for noise proportional to
// the response.)
//
// Without coherence the noise is modelled per channel as
//
//     s^2(f) = a exp(g x),    x = (f - f_mid) / (f_max - f_min)  in [-1/2, 1/2],
//
// a level that may drift across the band (a hammer's force spectrum rolls off, a sensor's noise floor is not
// white), with a and g by maximum likelihood. A part proportional to the response (force noise) is not modelled:
// a model's error at a resonance also grows with the response, and a fit that took it for noise would hide exactly
// the findings that matter (a frequency shift at every peak); with second differences, such a part would also
// absorb the curvature of lightly damped peaks. With coherence, the fit's coherence-based variance is used
// (frf_variance), averaged over five lines, and only the number of averages, its scale, is estimated the same way.
// An analyser's coherence comes from the same n averages as h: (1 - coh^2)/coh^2 |h|^2 is then the residual power of
// those averages, an estimate with 2 (n - 1) degrees of freedom that scatters from line to line (chi-square: with
// 8 averages a tenth of the lines read under 0.56 of its mean). Over one line that scatter made z's tail so
// heavy that a right model was called `unexplained` in 31 of 40 drawn mdof2 controls; the residual power of
// output noise over input power is smooth in frequency, so five lines pooled have five times the degrees of
// freedom, and the finding threshold counts what is left (`level_dof`; residual_analysis.hpp). A level that scatters
// by under 10 % from line to line (a coherence made from the exact noise level, test data) is kept line by line.
#pragma once

#include "mbgen/data/frf_data.hpp"

#include <Eigen/Core>

#include <string>

namespace mbgen {

struct FrfNoise {
  enum class Source {
    Coherence,    // the coherence's shape, scaled by the data's line-to-line scatter
    Scatter,      // the data's line-to-line scatter alone (no coherence)
    TooFewLines,  // fewer than kMinLines lines: the channel's RMS, as a last resort
  };
  static constexpr int kMinLines = 16;

  Eigen::VectorXd sigma;  // standard deviation of each measured complex value (total over real and imaginary part)
  Source source = Source::Scatter;
  // Coherence: the number of averages n whose variance (1 - coh^2)/(n coh^2) |h|^2 matches the data's scatter
  // (at least 1), and the factor then applied to it (1, or more where the scatter exceeds one average's).
  double averages = 1;
  double coherence_scale = 1;
  // Coherence: the degrees of freedom of sigma^2, pooled over five lines, as the data's own scatter of the
  // coherence-based variance from line to line shows it (0: it scatters by under 10 %, the level is taken as exact
  // and not pooled).
  double level_dof = 0;
  // Scatter: the fitted model s^2 = additive exp(drift x).
  double additive = 0, drift = 0;
  int lines_left_out = 0;  // lines whose second difference the response's curvature dominated

  // One phrase for reports: how the level was obtained.
  std::string description() const;
};

// The noise level of one measured channel at frequencies f_hz (increasing; the same length as its values).
FrfNoise frf_noise(const Eigen::VectorXd& f_hz, const FrfChannel& channel);

}  // namespace mbgen
