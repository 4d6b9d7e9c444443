#include "mbgen/frf_sigma.hpp"

#include <algorithm>
#include <cmath>

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
  return var;
}

}  // namespace mbgen
