#include "mbgen/dynamics/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace mbgen {
namespace {

// The loop of both ordered_parallel forms: `threads` workers from the start, and with `cores` one more whenever a
// core is free as a worker claims a task and another task is left for it.
void run_ordered(std::size_t count, int threads, ThreadBudget* cores, const std::function<void(std::size_t)>& task,
                 const std::function<void(std::size_t)>& done) {
  std::atomic<std::size_t> next{0};
  std::mutex mutex;  // guards finished, errors, reported and the done() calls
  std::vector<char> finished(count, 0);
  std::vector<std::exception_ptr> errors(count);
  std::size_t reported = 0;
  std::mutex pool_mutex;  // guards pool: workers may start workers
  std::vector<std::thread> pool;
  std::function<void()> work;
  const auto start_worker = [&](bool borrowed) {
    std::lock_guard<std::mutex> lock(pool_mutex);
    try {
      pool.emplace_back([&work, cores, borrowed] {
        work();
        if (borrowed) cores->give_back();
      });
    } catch (const std::system_error&) {
      if (borrowed) cores->give_back();  // no more threads to be had: the workers there are share the tasks
    }
  };
  work = [&] {
    for (;;) {
      // A task for this worker and at least one more left: a free core takes it.
      if (cores && next.load() + 1 < count && cores->try_take()) start_worker(true);
      const std::size_t i = next++;
      if (i >= count) return;
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
  for (std::size_t w = 1; w < workers; ++w) start_worker(false);
  work();
  // Waiting for workers, the caller lends its core (to the workers' nested loops, say).
  bool lent = false;
  if (cores) {
    std::lock_guard<std::mutex> lock(pool_mutex);
    lent = !pool.empty();
  }
  if (lent) cores->give_back();
  // Workers may have started workers: join until the pool stops growing (a worker adds to it before it ends).
  for (std::size_t j = 0;; ++j) {
    std::thread t;
    {
      std::lock_guard<std::mutex> lock(pool_mutex);
      if (j >= pool.size()) break;
      t = std::move(pool[j]);
    }
    t.join();
  }
  if (lent) cores->take_back();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace

void ordered_parallel(std::size_t count, int threads, const std::function<void(std::size_t)>& task,
                      const std::function<void(std::size_t)>& done) {
  run_ordered(count, threads, nullptr, task, done);
}

void ordered_parallel(std::size_t count, ThreadBudget& cores, const std::function<void(std::size_t)>& task,
                      const std::function<void(std::size_t)>& done) {
  run_ordered(count, 1, &cores, task, done);
}

void consume_while_producing(std::size_t count, ThreadBudget& cores, const std::function<void(std::size_t)>& produce,
                             const std::function<void()>& prepare, const std::function<void(std::size_t)>& consume) {
  const auto in_turn = [&] {
    for (std::size_t i = 0; i < count; ++i) produce(i);
    prepare();
    ordered_parallel(count, cores, consume, [](std::size_t) {});
  };
  if (!cores.try_take()) return in_turn();
  std::mutex mutex;  // guards produced and abandoned
  std::condition_variable ready;
  std::size_t produced = 0;  // produce(i) has returned for every i below
  bool abandoned = false;    // a produce() threw: no more consume()
  std::exception_ptr consumer_error;
  const auto consume_all = [&] {  // on the core just taken
    try {
      prepare();
      ordered_parallel(
          count, cores,
          [&](std::size_t i) {
            {
              std::unique_lock<std::mutex> lock(mutex);
              ready.wait(lock, [&] { return produced > i || abandoned; });
              if (produced <= i) return;
            }
            consume(i);
          },
          [](std::size_t) {});
    } catch (...) {
      consumer_error = std::current_exception();
    }
    cores.give_back();
  };
  std::thread consumers;
  try {
    consumers = std::thread(consume_all);
  } catch (const std::system_error&) {  // no thread to be had: the core back, and all on this thread
    cores.give_back();
    return in_turn();
  }
  std::exception_ptr producer_error;
  for (std::size_t i = 0; i < count; ++i) {
    try {
      produce(i);
    } catch (...) {
      producer_error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (producer_error)
        abandoned = true;
      else
        produced = i + 1;
    }
    ready.notify_all();
    if (producer_error) break;
  }
  cores.give_back();  // the caller's core, lent to the consumers while it waits
  consumers.join();
  cores.take_back();
  if (producer_error) std::rethrow_exception(producer_error);
  if (consumer_error) std::rethrow_exception(consumer_error);
}

void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& task) {
  ordered_parallel(count, threads, task, [](std::size_t) {});
}

}  // namespace mbgen
