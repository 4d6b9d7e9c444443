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
};

struct Discrepancy {
  // unexplained_resonance, unexplained_antiresonance, frequency_shift, damping_mismatch, static_compliance,
  // mass_line, phase_trend, misfit
  std::string kind;
  std::string channel, data_set;
  double f_hz = 0;              // the characteristic frequency (a peak of the data, or the band's centre)
  double f_lo = 0, f_hi = 0;    // the band
  double model_f_hz = 0;        // frequency_shift: the model's nearby peak
  double size_db = 0;           // |H_meas| / |H_model| at f_hz, in dB (positive: the data is larger)
  double significance = 0;      // mean normalized residual over the band (1 = noise level); phase_trend: slope / its std
  double delay_s = 0;           // phase_trend: the delay that explains it
  std::string text;             // one sentence
};

struct ResidualOptions {
  int window = 5;            // running-mean width in lines
  double threshold = 4.0;    // running mean of z above this is a finding (noise alone: ~1e-5 per line)
  double peak_tolerance = 0.03;  // relative frequency distance within which a data and a model peak are "the same"
};

struct ResidualSummary {
  std::vector<Discrepancy> discrepancies;  // strongest first
  double mean_z = 0;                       // mean normalized residual over all lines (1 = noise level)
  long lines = 0;
};

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
