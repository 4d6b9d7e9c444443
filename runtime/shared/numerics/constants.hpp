// Internal: the constants every area uses, written once. Each is the double nearest its exact value, so
// kTwoPi == 2 * M_PI exactly and results do not depend on which spelling a file used.
#pragma once

#include <complex>

namespace mbgen::numerics {

inline constexpr double kPi = 3.14159265358979323846264338327950288;
inline constexpr double kTwoPi = 6.28318530717958647692528676655900577;

// Radians to degrees, as (x * 180) / pi: the order in which every caller computed it, so printed digits stay.
inline double degrees(double radians) { return radians * 180 / kPi; }

// Natural frequency in Hz of a continuous-time pole lambda: |lambda| / 2 pi.
inline double pole_frequency_hz(std::complex<double> lambda) { return std::abs(lambda) / kTwoPi; }

// Damping ratio of a continuous-time pole: -Re lambda / |lambda|, 0 for the pole at the origin.
inline double pole_damping_ratio(std::complex<double> lambda) {
  const double magnitude = std::abs(lambda);
  return magnitude > 0 ? -lambda.real() / magnitude : 0.0;
}

}  // namespace mbgen::numerics
