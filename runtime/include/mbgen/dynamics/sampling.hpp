// Checks on sampled records (docs/interfaces.md: the time column is increasing and uniformly sampled).
#pragma once

#include <Eigen/Core>

namespace mbgen {

// The sampling interval of a uniformly sampled time column: (t_last - t_0) / (samples - 1). Throws
// DynamicsError, naming the first offending sample, if there are fewer than two samples, a time is not finite or
// not increasing, or some t_k deviates from t_0 + k dt by more than relative_tolerance * dt (the default allows
// for times printed with a limited number of digits, not for a missing or repeated sample).
double uniform_sample_interval(const Eigen::VectorXd& time, double relative_tolerance = 1e-3);

}  // namespace mbgen
