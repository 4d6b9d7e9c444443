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
  // explain, (1 - coh^2) Gyy [Gxx^-1]_ii / (segments - inputs) (Bendat & Piersol, Random Data, 9.90, with the
  // degrees of freedom of the residual power; the overlapping Hann segments give about segments / 1.06 independent
  // averages, so it is still low by ~6 %). Unlike the textbook form
  // (1 - coh^2) / (coh^2 n) |H|^2 it needs no estimated |H| and no division by a small coherence, so it stays a
  // noise level where H is small: e.g. for the residual of a nearly right model.
  std::vector<Eigen::VectorXd> variance;
  Eigen::Index segments = 0;           // number of averaged segments
  double dt = 0;                       // sample interval of the record
  std::vector<Eigen::Index> dropped_bins;
};

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
