// What a simulation gets wrong: the residual between measured and model FRFs, judged against the noise level,
// turned into findings a test engineer can read ("an unexplained resonance near 190 Hz on xs_front/Fx, 14 dB").
//
// Each channel carries the measured FRF, the model's FRF and the standard deviation of the measurement per line
// (from coherence; see fit.hpp FrfWeighting). The normalized residual z = |H_meas - H_model|^2 / sigma^2 has
// mean 1 where only noise remains. Bands where its running mean stays above a threshold are findings; each is
// classified by what the measured and model magnitudes do there.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <complex>

#include <string>
#include <vector>

namespace mbgen {

struct ChannelResidual {
  std::string channel;          // "OUTPUT/INPUT"
  std::string data_set;         // the data file, for messages
  std::vector<double> f_hz;     // increasing
  Eigen::VectorXcd measured, model;
  Eigen::VectorXd sigma;        // standard deviation of the measured complex value (total, not per part)
  std::string noise;            // how sigma was obtained, one phrase (frf_noise.hpp; a record's residual H1)
  long lines_not_judged = 0;    // lines left out because the data there are noise (measured and model below it)
  // The correlation of the noise at a line with that at its j-th neighbour, j = 1, 2, ... (empty: independent lines,
  // as assumed for measured FRFs). A record's H1 lines share its segments' windowed spectra (welch.hpp).
  std::vector<double> line_correlation;
  // The degrees of freedom of sigma^2 where it is an estimate from a few averages (a record's H1 variance over five
  // lines, a measured FRF's coherence-based variance over five lines where the coherence scatters: frf_noise.hpp),
  // 0 where it is taken as exact: an estimated level scatters, and z over it has a heavier tail.
  double sigma_dof = 0;
};

struct Discrepancy {
  // unexplained_resonance, unexplained_antiresonance, frequency_shift, damping_mismatch, static_compliance,
  // mass_line, phase_trend, misfit; parameter_at_bound (the fit pressed `parameter` against a bound: the model
  // fits the data only with values it does not allow)
  std::string kind;
  std::string parameter;        // parameter_at_bound: its name
  std::string channel, data_set;
  double f_hz = 0;              // the characteristic frequency (a peak of the data, or the band's centre)
  double f_lo = 0, f_hi = 0;    // the band
  double model_f_hz = 0;        // frequency_shift: the model's nearby peak
  // |H_meas| / |H_model| at f_hz in dB (positive: the data is larger), each magnitude at least the noise level
  // there, so no size exceeds what the data can tell; unexplained_resonance: the peak's rise above the response
  // around it (what the model would have to add)
  double size_db = 0;
  double significance = 0;      // mean normalized residual over the band (1 = noise level); phase_trend: slope / its std
  double delay_s = 0;           // phase_trend: the delay that explains it
  std::string text;             // one sentence
};

struct ResidualOptions {
  int window = 5;            // running-mean width in lines
  // A running mean of z above the finding threshold is a finding. The threshold is at least `threshold` (noise
  // alone exceeds 4 in ~1.7e-5 of the windows) and high enough that noise alone is expected to raise at most
  // `false_alarm_rate` windows over all the lines judged (finding_threshold): at a fixed 4, noise alone gave a
  // finding in about a quarter of the diagnoses of a 9-channel 4096-line FRF matrix (residual_analysis_test).
  double threshold = 4.0;
  double false_alarm_rate = 0.05;
  double peak_tolerance = 0.03;  // relative frequency distance within which a data and a model peak are "the same"
  // Where the model misses a channel throughout (a band wider than `wide_band` lines), the residual's own floor
  // there is far above the noise, and what matters is what stands out of that floor: sub-bands whose running
  // mean exceeds `contrast` times the floor (its running median over `floor_window` lines) are findings of their
  // own, beside the wide band's (a mode outside a lumped model, two decades above a misfit it has everywhere).
  int wide_band = 60;
  double contrast = 30.0;
  int floor_window = 41;
};

struct ResidualSummary {
  std::vector<Discrepancy> discrepancies;  // strongest first
  double mean_z = 0;                       // mean normalized residual over all lines (1 = noise level)
  long lines = 0;
  double threshold = 0;                    // the finding threshold used (finding_threshold of `lines`)
};

// The level a running mean of z over `options.window` lines must exceed to be a finding when `lines` lines are
// judged: the lowest level at or above `options.threshold` at which the expected number of windows that noise
// alone raises above it, lines x P(mean of window Exp(1) variables > level), is at most `false_alarm_rate`
// (a union bound: overlapping windows make it conservative).
double finding_threshold(const ResidualOptions& options, long lines);

// The same over channels whose neighbouring lines may be correlated (ChannelResidual::line_correlation): a window's
// mean of z is then a sum of exponentials weighted by the eigenvalues of its lines' correlation matrix, whose tail
// is heavier (with a Hann window's H1, P(mean of 5 > 4) is 2.4e-4 instead of 1.7e-5), and heavier again where sigma^2
// is an estimate of `sigma_dof` degrees of freedom (the tail averaged over its chi-square scatter; 6.7e-4 at 100;
// independent lines with such a level: 2.4e-4 at 70); the expected number of windows above the level is summed over
// the channels.
double finding_threshold(const ResidualOptions& options, const std::vector<ChannelResidual>& channels);

ResidualSummary analyse_residuals(const std::vector<ChannelResidual>& channels, const ResidualOptions& options = {});

// The normalized residual z of one line: |measured - model|^2 / sigma^2 (1 where only noise remains).
inline double normalized_residual(const std::complex<double>& measured, const std::complex<double>& model, double sigma) {
  return std::norm(measured - model) / std::max(sigma * sigma, 1e-300);
}

// Local maxima of |h| that stand out of their neighbourhood by `prominence_db`, as indices (for peak finding).
std::vector<int> magnitude_peaks(const Eigen::VectorXcd& h, double prominence_db = 3.0);

// How far |h[i]| rises above the higher of the lowest points on either side before a higher point (or the end),
// in dB; minus infinity when i is no local maximum. Independent of the FRF's scale, unlike the height itself.
double peak_prominence_db(const Eigen::VectorXcd& h, int i);

}  // namespace mbgen
