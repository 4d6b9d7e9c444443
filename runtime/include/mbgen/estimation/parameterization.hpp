// Physical bounds by reparameterisation (no penalty functions).
//
// The optimiser works on an unconstrained internal coordinate theta; the physical value is p = map(theta):
//
//   no bounds         p = s theta                          (s = |nominal|, or 1 when the nominal is 0)
//   [lo, +inf)        p = lo + s exp(theta)                (s = nominal - lo when positive: theta = 0 at nominal)
//   (-inf, hi]        p = hi - s exp(theta)
//   [lo, hi]          p = lo + (hi - lo) / (1 + exp(-theta))   (logistic)
//
// So a step in theta is a relative change of the parameter (scaled by its nominal value), every theta maps to
// a physically admissible value, and the thesis's penalty-function trap (Sec. 4.3) cannot arise. A value
// exactly on a bound is unreachable (theta = -inf): starting points on a bound are moved inside by
// kBoundaryOffset of the scale.
#pragma once

#include "mbgen/model.hpp"

#include <string>

namespace mbgen {

enum class BoundKind { None, Lower, Upper, Interval };

struct ParameterTransform {
  BoundKind kind = BoundKind::None;
  double lower = 0, upper = 0;
  double scale = 1;

  double to_physical(double theta) const;
  // Inverse map; values on or outside a bound are first moved inside (see kBoundaryOffset).
  double to_internal(double p) const;
  // dp / dtheta at theta.
  double derivative(double theta) const;
};

constexpr double kBoundaryOffset = 1e-6;

// "lower" or "upper" when an estimate `value` with standard deviation `std` lies on that bound of `t`, else "": within
// kAtBoundTolerance of the transform's scale of it (the optimiser drove theta towards infinity: the data pull the
// parameter beyond the bound) and no farther from it than its std (a well-determined small value near a bound stays
// an interior estimate). A linearised std means nothing there: the cost is not stationary at a bound.
constexpr double kAtBoundTolerance = 1e-6;
std::string bound_reached(const ParameterTransform& t, double value, double std);

// The transform for a parameter with the bounds of `info`, scaled by `nominal` (its prior value).
// Throws std::invalid_argument if lower > upper or the nominal lies outside the bounds.
ParameterTransform make_parameter_transform(const ParameterInfo& info, double nominal);

}  // namespace mbgen
