#include "multistart.hpp"

#include "mbgen/parallel.hpp"

#include <algorithm>

namespace mbgen::estimation {

StartSampler::StartSampler(std::uint64_t seed) : engine_(seed) {}

double StartSampler::symmetric_unit() {
  const double unit = double(engine_() >> 11) * (1.0 / 9007199254740992.0);  // [0, 1)
  return 2 * unit - 1;
}

std::vector<LmResult> run_starts(int count, int threads, const std::function<LmResult(int)>& local) {
  std::vector<LmResult> results(static_cast<std::size_t>(std::max(count, 0)));
  parallel_for(results.size(), threads, [&](std::size_t i) { results[i] = local(static_cast<int>(i)); });
  return results;
}

int best_start(const std::vector<LmResult>& results) {
  int best = 0;
  for (std::size_t i = 1; i < results.size(); ++i)
    if (results[i].cost < results[static_cast<std::size_t>(best)].cost) best = static_cast<int>(i);
  return best;
}

}  // namespace mbgen::estimation
