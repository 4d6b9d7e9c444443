// Welch estimate of FRFs (H1) and coherence from a time record. Choices and trade-offs: docs/data.md.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <string>
#include <vector>

#include "mbgen/data/frf_data.hpp"
#include "mbgen/data/time_record.hpp"

namespace mbgen {

enum class WelchWindow { Hann, Hamming, Rectangular };  // periodic forms, as for spectral analysis

struct WelchOptions {
  Eigen::Index segment_length = 1024;  // samples per segment (FFT length); frequency resolution 1/(L dt)
  double overlap = 0.5;                // fraction of a segment shared with the next one, in [0, 1)
  WelchWindow window = WelchWindow::Hann;
  // Divide H1 by zero_order_hold_response() when the record's inputs are held (HoldMode::ZeroOrder), so that
  // the estimate approximates the continuous-time FRF (up to aliasing). Ignored for `# hold=none` records.
  bool compensate_hold = false;
};

struct WelchEstimate {
  // One channel per (output, input), outputs outer. Frequencies k / (L dt), k = 0 .. L/2, except the bins
  // where the inputs' auto-spectral matrix is singular (see `dropped_bins`). Each channel's coherence is the
  // multiple coherence of its output with all inputs (the ordinary coherence for one input).
  FrfData frf;
  // Per channel of `frf` (same order) and frequency: the variance of H1 from the output power the inputs do not
  // explain, (1 - coh^2) Gyy [Gxx^-1]_ii c / (segments - inputs) (Bendat & Piersol, Random Data, 9.90, with the
  // degrees of freedom of the residual power), c the overlap factor: overlapping segments average less of the noise
  // away than independent ones (Welch 1967; 50 % overlapping Hann segments: c ~ 1.056). Unlike the textbook form
  // (1 - coh^2) / (coh^2 n) |H|^2 it needs no estimated |H| and no division by a small coherence, so it stays a
  // noise level where H is small: e.g. for the residual of a nearly right model.
  std::vector<Eigen::VectorXd> variance;
  Eigen::Index segments = 0;           // number of averaged segments
  double dt = 0;                       // sample interval of the record
  std::vector<Eigen::Index> dropped_bins;
};

// The correlation of H1's errors at a line with those at its j-th neighbour (j = 1 .. count) for these options:
// each segment's noise and input spectra at neighbouring bins correlate as the window's squared transform,
// c_j = sum w^2 e^(-2 pi i j n / L) / sum w^2 (Hann: -2/3, 1/6), and H1's error with their product, |c_j|^2
// (Hann: 4/9, 1/36), for spectra about flat over a few bins.
std::vector<double> welch_line_correlation(const WelchOptions& options, int count);

// The degrees of freedom of one line's WelchEstimate::variance from `segments` segments and `inputs` inputs:
// 2 (segments - inputs) / c, c the overlap factor (the unexplained power is a sum over the segments of complex
// squares, less one per input fitted, and overlapping segments count as fewer).
double welch_variance_dof(const WelchOptions& options, Eigen::Index segments, Eigen::Index inputs);

// H1 = Gyx Gxx^{-1} (for one input Gyx / Gxx), with linearly averaged one-sided cross spectra of windowed,
// overlapping segments. Throws DataError for unknown signals, a record shorter than one segment, fewer
// segments than inputs, or bad options.
WelchEstimate welch_h1(const TimeRecord& record, const std::vector<std::string>& inputs,
                       const std::vector<std::string>& outputs, const WelchOptions& options = {});

// Frequency response of holding a sample for dt, relative to the sample itself: exp(-i pi f dt) sinc(pi f dt)
// (a half-sample delay and a droop of 2/pi at Nyquist). A held record's H1 is about G(i 2 pi f) times this.
std::complex<double> zero_order_hold_response(double f_hz, double dt);

// Divides every channel of `frf` by zero_order_hold_response(f, dt).
void remove_zero_order_hold(FrfData& frf, double dt);

}  // namespace mbgen
