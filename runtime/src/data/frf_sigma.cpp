#include "mbgen/data/frf_sigma.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "numerics/window_median.hpp"

namespace mbgen {

Eigen::VectorXd frf_variance(const FrfChannel& channel, double averages, double floor) {
  const Eigen::VectorXd mag = channel.values.cwiseAbs();
  const Eigen::Index n = mag.size();
  const double rms = n > 0 ? std::sqrt(mag.squaredNorm() / double(n)) : 0.0;
  const double level = rms > 0 ? rms : 1.0;  // an all-zero channel: unit weights rather than a division by zero
  const double floor2 = std::pow(floor * level, 2);
  const double n_avg = std::max(averages, 1.0);
  Eigen::VectorXd var(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    double v = level * level;
    if (channel.coherence) {
      const double g2 = std::min(std::max((*channel.coherence)[k], 1e-12), 1.0);
      v = (1 - g2) / (g2 * n_avg) * mag[k] * mag[k];
    }
    var[k] = std::max(v, floor2);
  }
  if (channel.coherence) {
    // A coherence is printed with a few digits (six in a CSV, a float's seven in UFF): at a resonance 70 dB above
    // the noise 1 - g2 falls below the last digit and reads 0, or keeps one uncertain digit, and the line got up to
    // (1 / floor)^2 = 10^6 times the weight its neighbours' noise supports (a fit then passed exactly through it).
    // The residual power is a smooth spectrum across a few lines: where 1 - g2 is under 1e-5 (one or no digit
    // left in six), a line's variance is taken at least a quarter of the median over its nine-line neighbourhood.
    // Only there: elsewhere the printed value is exact enough, and a floor everywhere changed the weights of
    // few-average estimates (a record's Welch H1) enough to move a multi-start search to another optimum.
    const Eigen::VectorXd raw = var;
    std::vector<double> window;
    for (Eigen::Index k = 0; k < n; ++k) {
      if (!(1.0 - (*channel.coherence)[k] < 1e-5)) continue;
      const Eigen::Index lo = std::max<Eigen::Index>(0, k - 4), hi = std::min<Eigen::Index>(n - 1, k + 4);
      var[k] = std::max(raw[k], 0.25 * detail::window_median(raw.data() + lo, raw.data() + hi + 1, window));
    }
  }
  return var;
}

}  // namespace mbgen
