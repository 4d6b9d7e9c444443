// The median of a short window of values, for running medians (a smooth local level that peaks do not pull):
// the upper median, found by partial sorting in a scratch buffer the caller keeps between calls.
#pragma once

#include <algorithm>
#include <vector>

namespace mbgen::detail {

inline double window_median(const double* first, const double* last, std::vector<double>& scratch) {
  scratch.assign(first, last);
  const auto middle = scratch.begin() + static_cast<long>(scratch.size() / 2);
  std::nth_element(scratch.begin(), middle, scratch.end());
  return *middle;
}

}  // namespace mbgen::detail
