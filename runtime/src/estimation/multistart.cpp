#include "multistart.hpp"

#include "mbgen/dynamics/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace mbgen::estimation {

StartSampler::StartSampler(std::uint64_t seed) : engine_(seed) {}

double StartSampler::symmetric_unit() {
  const double unit = double(engine_() >> 11) * (1.0 / 9007199254740992.0);  // [0, 1)
  return 2 * unit - 1;
}

namespace {

void run_ordered(std::size_t count, int threads, ThreadBudget* cores, const std::function<void(std::size_t)>& task,
                 const std::function<void(std::size_t)>& done) {
  if (cores) ordered_parallel(count, *cores, task, done);
  else ordered_parallel(count, threads, task, done);
}

}  // namespace

std::vector<LmResult> run_starts(int count, int threads, const std::function<LmResult(int)>& local,
                                 ThreadBudget* cores) {
  std::vector<LmResult> results(static_cast<std::size_t>(std::max(count, 0)));
  run_ordered(
      results.size(), threads, cores, [&](std::size_t i) { results[i] = local(static_cast<int>(i)); },
      [](std::size_t) {});
  return results;
}

bool starts_agree(const std::vector<LmResult>& results, std::size_t n, const AgreementRule& rule) {
  if (rule.agree <= 0 || n < static_cast<std::size_t>(rule.agree)) return false;
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) lowest = std::min(lowest, results[i].cost);
  if (!std::isfinite(lowest) || !(lowest <= rule.ceiling)) return false;
  int agreeing = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (results[i].cost <= lowest + rule.tolerance * std::abs(lowest)) ++agreeing;
  return agreeing >= rule.agree;
}

std::vector<LmResult> run_starts_until_agreed(int count, int threads, const AgreementRule& rule,
                                              const AbandonableStart& local, ThreadBudget* cores) {
  const std::size_t n = static_cast<std::size_t>(std::max(count, 0));
  std::vector<LmResult> results(n);
  // The last start that counts; lowered (once, in index order) when the starts up to it agree.
  std::atomic<std::size_t> last{n == 0 ? 0 : n - 1};
  run_ordered(
      n, threads, cores,
      [&](std::size_t i) {
        if (i > last.load()) return;
        try {
          results[i] = local(static_cast<int>(i), [&last, i] { return i > last.load(); });
        } catch (...) {
          if (i > last.load()) return;  // abandoned anyway
          throw;
        }
      },
      [&](std::size_t i) {
        if (i <= last.load() && i + 1 < n && starts_agree(results, i + 1, rule)) last.store(i);
      });
  results.resize(n == 0 ? 0 : last.load() + 1);
  return results;
}

int best_start(const std::vector<LmResult>& results) {
  int best = 0;
  for (std::size_t i = 1; i < results.size(); ++i)
    if (results[i].cost < results[static_cast<std::size_t>(best)].cost) best = static_cast<int>(i);
  return best;
}

}  // namespace mbgen::estimation
