// Deterministic multi-start of local fits on worker threads. Internal header.
#pragma once

#include "levenberg_marquardt.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <random>
#include <functional>
#include <vector>

namespace mbgen::estimation {

// Uniform numbers in [-1, 1) from a std::mt19937_64, with the conversion written out (53 bits), so that the
// starts are identical on every standard library (std::uniform_real_distribution is implementation-defined).
class StartSampler {
 public:
  explicit StartSampler(std::uint64_t seed);
  double symmetric_unit();

 private:
  std::mt19937_64 engine_;
};

// Runs `local(i)` for i = 0..count-1 on `threads` workers; returns the results by index. The first exception
// (lowest index) is rethrown after all workers have finished.
std::vector<LmResult> run_starts(int count, int threads, const std::function<LmResult(int)>& local);

// Index of the lowest cost, ties to the lower index.
int best_start(const std::vector<LmResult>& results);

}  // namespace mbgen::estimation
