// Wall-clock seconds since t0, for the benchmarks' stage timings.
#pragma once

#include <chrono>

namespace mbgen::bench {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace mbgen::bench
