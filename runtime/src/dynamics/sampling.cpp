#include "mbgen/dynamics/sampling.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"

#include <cmath>
#include <sstream>

namespace mbgen {

double uniform_sample_interval(const Eigen::VectorXd& time, double relative_tolerance) {
  const Eigen::Index n = time.size();
  if (n < 2) throw DynamicsError("time column: need at least two samples to know the sampling interval, got " +
                                 std::to_string(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    if (!std::isfinite(time[k])) {
      std::ostringstream msg;
      msg << "time column: sample " << k << " is not finite";
      throw DynamicsError(msg.str());
    }
    if (k > 0 && !(time[k] > time[k - 1])) {
      std::ostringstream msg;
      msg << "time column: not increasing at sample " << k << " (t = " << time[k - 1] << " then " << time[k] << ")";
      throw DynamicsError(msg.str());
    }
  }
  const double dt = (time[n - 1] - time[0]) / static_cast<double>(n - 1);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double expected = time[0] + static_cast<double>(k) * dt;
    if (std::abs(time[k] - expected) > relative_tolerance * dt) {
      std::ostringstream msg;
      msg.precision(10);
      msg << "time column: not uniformly sampled: sample " << k << " is at t = " << time[k] << ", expected "
          << expected << " for the mean interval dt = " << dt;
      throw DynamicsError(msg.str());
    }
  }
  return dt;
}

}  // namespace mbgen
