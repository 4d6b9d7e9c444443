// The standard deviation of a measured FRF value: the one formula behind the fit's weights (estimation), the
// diagnosis's validation error and the shape of the data-driven noise level (frf_noise.hpp).
//
// With a coherence column g2 (the ordinary coherence function, 0..1), the variance of the H1 estimate h from n
// averages (Bendat & Piersol) is
//
//     var(h) = (1 - g2) / (n g2) |h|^2,
//
// taken with the measured |h|. An analyser computes g2 from the same averages as h: g2 = |h|^2 / (|h|^2 + s^2),
// s^2 the output power the input does not explain, per unit input power. So (1 - g2)/g2 |h|^2 = s^2: the product
// is the residual power of the least-squares estimate h, which for Gaussian noise is independent of h's own error.
// Weights from it do not favour the lines whose noise happened to shrink |h|, and the fit stays unbiased. A model's
// |H| in place of |h| would bring that correlation back (through the 1/|h|^2 in (1 - g2)/g2): on simulated H1
// estimates of mdof2 from 5 to 50 averages it made the reported std 1.7 to 3 times too large (bench/README.md).
// A coherence that does not come from the same averages as h (e.g. computed from a noise-free response, as the test
// data generator once did) breaks the identity, and this formula then biases the estimates.
//
// Without coherence, every line of a channel gets the channel's RMS |h| (the channels balanced by their size).
// In both cases var >= (floor RMS|h|)^2, so that a coherence of exactly 1 does not give infinite weight. And where
// the coherence is printed too close to 1 to carry 1 - g2 (under 1e-5: a resonance far above the noise, six digits),
// a line's variance is at least a quarter of its neighbours' median (frf_sigma.cpp says why).
//
// Relation to frf_noise.hpp: the fit needs only relative weights (it estimates the noise's scale from its residuals,
// s^2 = RSS / (n - k)), so n (FrfWeighting::averages, default 1) only matters when several data sets are fitted
// together. The diagnosis's residual analysis needs an absolute level: frf_noise takes this formula's shape and
// estimates n from the data's line-to-line scatter (and without coherence, models the level from the scatter alone).
#pragma once

#include "mbgen/data/frf_data.hpp"

#include <Eigen/Core>

namespace mbgen {

struct FrfWeighting {
  int averages = 1;     // n, the number of averages behind the coherence
  double floor = 1e-3;  // the smallest standard deviation, relative to the channel's RMS |h|
};

// The variance of each measured complex value of `channel` (over real and imaginary part together: each part has
// half of it), n = `averages` (at least 1), at least (`floor` times the channel's RMS |h|)^2.
Eigen::VectorXd frf_variance(const FrfChannel& channel, double averages, double floor);
inline Eigen::VectorXd frf_variance(const FrfChannel& channel, const FrfWeighting& weighting) {
  return frf_variance(channel, weighting.averages, weighting.floor);
}

}  // namespace mbgen
