// FRFs estimated from time records, for the global search of a time-domain fit (and a diagnosis's screening of
// candidates).
//
// A time-domain output-error evaluation simulates the model with all parameter sensitivities over every sample,
// and from a poor start its cost is as multimodal as an FRF cost (a model mode on the wrong side of a measured
// one). The multi-start search therefore runs on the records' Welch H1 estimates with coherence (cheap, and
// their log-ratio residuals stay informative far from the optimum); only the best start is refined on the
// records themselves, so the estimate and its uncertainty remain the time-domain output-error optimum.
#pragma once

#include "mbgen/estimation/fit.hpp"

#include <optional>
#include <vector>

namespace mbgen::estimation {

struct SpectralCompanion {
  std::vector<DataSet> data;  // FRF data sets kept as they are; each record replaced by its H1 estimate
  int averages = 1;           // fewest Welch segments of any record (the FRF weighting's averages)
};

// Segment length: the largest power of two with at least 8 segments per record (at most 4096 samples); only
// frequencies in (0, 0.5 Nyquist] are kept, where the hold-compensated H1 approximates the continuous FRF
// (aliasing of lightly damped modes well below Nyquist is small). Returns nothing when there is no record or a
// record is too short for 8 segments of 64 samples: the caller then searches on the records directly.
std::optional<SpectralCompanion> spectral_companion(const ModelInfo& info, const std::vector<DataSet>& data);

// The same with the estimator's own bias at parameters `p` divided out: each record's H1 line multiplied by
// H(p) / H1_p, where H1_p is the same estimate (segments, window, hold compensation) of the model's response
// simulated from the record's inputs. An H1 of finite resolution flattens a lightly damped peak (at 4 Hz lines a
// spindle mode comes out 2.4 dB low); compared with exact model FRFs, that bias is a misfit which a richer model can
// take up, so that a model right on the records would show "evidence" for an extension on the plain H1. Take `p`
// where a model fitted to the records puts its modes, the data's: models that keep them are then judged on these
// FRFs as the records judge them. The ratio is sharp at a lightly damped mode: taken at a model whose mode lies half
// a line off, it moves the flattened peak instead of undoing it. Lines where H1_p vanishes keep their value.
std::optional<SpectralCompanion> debiased_spectral_companion(const Model& model, const Eigen::VectorXd& p,
                                                             const std::vector<DataSet>& data);

}  // namespace mbgen::estimation
