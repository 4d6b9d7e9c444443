#include "mbgen/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace mbgen {

void ordered_parallel(std::size_t count, int threads, const std::function<void(std::size_t)>& task,
                      const std::function<void(std::size_t)>& done) {
  std::atomic<std::size_t> next{0};
  std::mutex mutex;  // guards finished, errors, reported and the done() calls
  std::vector<char> finished(count, 0);
  std::vector<std::exception_ptr> errors(count);
  std::size_t reported = 0;
  auto work = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      std::exception_ptr error;
      try {
        task(i);
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex);
      finished[i] = 1;
      errors[i] = error;
      while (reported < count && finished[reported] && !errors[reported]) {
        // done() may throw too; it then counts as that index's error, and nothing later is reported.
        try {
          done(reported);
        } catch (...) {
          errors[reported] = std::current_exception();
          break;
        }
        ++reported;
      }
    }
  };
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), count);
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the workers there are share the tasks
    }
  }
  work();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& task) {
  ordered_parallel(count, threads, task, [](std::size_t) {});
}

}  // namespace mbgen
