#include "multistart.hpp"

#include <atomic>
#include <exception>
#include <thread>

namespace mbgen::estimation {

StartSampler::StartSampler(std::uint64_t seed) : engine_(seed) {}

double StartSampler::symmetric_unit() {
  const double unit = double(engine_() >> 11) * (1.0 / 9007199254740992.0);  // [0, 1)
  return 2 * unit - 1;
}

std::vector<LmResult> run_starts(int count, int threads, const std::function<LmResult(int)>& local) {
  std::vector<LmResult> results(static_cast<std::size_t>(count));
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(count));
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int i = next++; i < count; i = next++) {
      try {
        results[static_cast<std::size_t>(i)] = local(i);
      } catch (...) {
        errors[static_cast<std::size_t>(i)] = std::current_exception();
      }
    }
  };
  const int n = std::max(1, std::min(threads, count));
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return results;
}

int best_start(const std::vector<LmResult>& results) {
  int best = 0;
  for (std::size_t i = 1; i < results.size(); ++i)
    if (results[i].cost < results[static_cast<std::size_t>(best)].cost) best = static_cast<int>(i);
  return best;
}

}  // namespace mbgen::estimation
