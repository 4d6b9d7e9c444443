#include "mbgen/estimation/parameterization.hpp"

#include <cmath>
#include <stdexcept>

namespace mbgen {

ParameterTransform make_parameter_transform(const ParameterInfo& info, double nominal) {
  const bool has_lo = std::isfinite(info.lower), has_hi = std::isfinite(info.upper);
  if (has_lo && has_hi && !(info.lower < info.upper))
    throw std::invalid_argument("parameter " + info.name + ": lower bound is not below the upper bound");
  if ((has_lo && nominal < info.lower) || (has_hi && nominal > info.upper))
    throw std::invalid_argument("parameter " + info.name + ": value " + std::to_string(nominal) +
                                " lies outside its bounds");
  ParameterTransform t;
  t.lower = info.lower;
  t.upper = info.upper;
  const double magnitude = nominal != 0 ? std::abs(nominal) : 1.0;
  if (has_lo && has_hi) {
    t.kind = BoundKind::Interval;
    t.scale = info.upper - info.lower;
  } else if (has_lo) {
    t.kind = BoundKind::Lower;
    t.scale = nominal > info.lower ? nominal - info.lower : magnitude;
  } else if (has_hi) {
    t.kind = BoundKind::Upper;
    t.scale = nominal < info.upper ? info.upper - nominal : magnitude;
  } else {
    t.kind = BoundKind::None;
    t.scale = magnitude;
  }
  return t;
}

std::string bound_reached(const ParameterTransform& t, double value, double std) {
  const bool lower = t.kind == BoundKind::Lower || t.kind == BoundKind::Interval;
  const bool upper = t.kind == BoundKind::Upper || t.kind == BoundKind::Interval;
  const double reach = kAtBoundTolerance * t.scale;
  auto on = [&](double distance) { return distance <= reach && !(distance > std); };  // a NaN std counts as wide
  if (lower && on(value - t.lower)) return "lower";
  if (upper && on(t.upper - value)) return "upper";
  return "";
}

double ParameterTransform::to_physical(double theta) const {
  switch (kind) {
    case BoundKind::None: return scale * theta;
    case BoundKind::Lower: return lower + scale * std::exp(theta);
    case BoundKind::Upper: return upper - scale * std::exp(theta);
    case BoundKind::Interval: return lower + scale / (1 + std::exp(-theta));
  }
  return 0;
}

double ParameterTransform::to_internal(double p) const {
  const double inside = kBoundaryOffset * scale;
  switch (kind) {
    case BoundKind::None: return p / scale;
    case BoundKind::Lower: return std::log(std::max(p - lower, inside) / scale);
    case BoundKind::Upper: return std::log(std::max(upper - p, inside) / scale);
    case BoundKind::Interval: {
      const double x = std::min(std::max((p - lower) / scale, kBoundaryOffset), 1 - kBoundaryOffset);
      return std::log(x / (1 - x));
    }
  }
  return 0;
}

double ParameterTransform::derivative(double theta) const {
  switch (kind) {
    case BoundKind::None: return scale;
    case BoundKind::Lower: return scale * std::exp(theta);
    case BoundKind::Upper: return -scale * std::exp(theta);
    case BoundKind::Interval: {
      const double e = std::exp(-std::abs(theta));  // symmetric form, no overflow
      return scale * e / ((1 + e) * (1 + e));
    }
  }
  return 0;
}

}  // namespace mbgen
