#include "mbgen/dynamics/parallel.hpp"

#include <catch2/catch.hpp>

#include <atomic>
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace mbgen {
namespace {

TEST_CASE("ordered_parallel: every task once, reported in index order although they finish out of order") {
  const std::size_t n = 9;
  std::vector<std::atomic<int>> runs(n);
  std::vector<std::size_t> reported;
  ordered_parallel(
      n, 2,
      [&](std::size_t i) {
        // Even tasks take longer: the odd ones on the other worker finish first.
        if (i % 2 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
        ++runs[i];
      },
      [&](std::size_t i) { reported.push_back(i); });
  for (std::size_t i = 0; i < n; ++i) CHECK(runs[i] == 1);
  std::vector<std::size_t> expected(n);
  for (std::size_t i = 0; i < n; ++i) expected[i] = i;
  CHECK(reported == expected);
}

// Tasks 2 and 4 throw: `run(task, done)` runs six tasks the way under test.
void check_lowest_failure_rethrown(
    const std::function<void(const std::function<void(std::size_t)>&, const std::function<void(std::size_t)>&)>& run) {
  std::vector<std::size_t> reported;
  const auto failing = [](std::size_t i) {
    if (i == 4) throw std::runtime_error("task 4");
    if (i == 2) throw std::runtime_error("task 2");
  };
  CHECK_THROWS_WITH(run(failing, [&](std::size_t i) { reported.push_back(i); }), "task 2");
  CHECK(reported == std::vector<std::size_t>{0, 1});
}

TEST_CASE("ordered_parallel: the lowest failing index's exception, nothing reported from it on") {
  check_lowest_failure_rethrown([](const auto& task, const auto& done) { ordered_parallel(6, 2, task, done); });
}

TEST_CASE("ordered_parallel: no tasks, one worker") {
  int calls = 0;
  ordered_parallel(0, 2, [&](std::size_t) { ++calls; }, [&](std::size_t) { ++calls; });
  ordered_parallel(3, 1, [&](std::size_t) { ++calls; }, [&](std::size_t) { ++calls; });
  CHECK(calls == 6);
}

TEST_CASE("ordered_parallel on a budget: every task once, in index order, and every core given back") {
  ThreadBudget cores(3);
  const std::size_t n = 12;
  std::vector<std::atomic<int>> runs(n);
  std::vector<std::size_t> reported;
  ordered_parallel(
      n, cores,
      [&](std::size_t i) {
        if (i % 3 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(3));
        ++runs[i];
      },
      [&](std::size_t i) { reported.push_back(i); });
  for (std::size_t i = 0; i < n; ++i) CHECK(runs[i] == 1);
  CHECK(reported.size() == n);
  CHECK(std::is_sorted(reported.begin(), reported.end()));
  CHECK(cores.free_cores() == 2);
}

TEST_CASE("ordered_parallel on a budget: a core that finds no task left joins a nested loop, never more than the "
          "budget's cores at once") {
  ThreadBudget cores(2);
  std::mutex mutex;
  std::set<std::thread::id> inner_threads;
  std::atomic<int> busy{0}, most_busy{0};
  const auto enter = [&] {
    const int now = ++busy;
    int seen = most_busy.load();
    while (now > seen && !most_busy.compare_exchange_weak(seen, now)) {
    }
  };
  // Outer task 0 is short; outer task 1 runs six inner tasks one after the other unless a core joins it.
  ordered_parallel(
      2, cores,
      [&](std::size_t outer) {
        if (outer == 0) return;
        ordered_parallel(
            6, cores,
            [&](std::size_t) {
              enter();
              {
                std::lock_guard<std::mutex> lock(mutex);
                inner_threads.insert(std::this_thread::get_id());
              }
              std::this_thread::sleep_for(std::chrono::milliseconds(20));
              --busy;
            },
            [](std::size_t) {});
      },
      [](std::size_t) {});
  CHECK(inner_threads.size() >= 2);
  CHECK(most_busy.load() <= 2);
  CHECK(cores.free_cores() == 1);
}

TEST_CASE("ordered_parallel on a budget: the lowest failing index's exception, cores given back") {
  ThreadBudget cores(2);
  check_lowest_failure_rethrown([&](const auto& task, const auto& done) { ordered_parallel(6, cores, task, done); });
  CHECK(cores.free_cores() == 1);
}

TEST_CASE("ThreadBudget: a single core has none to lend, and a loop on it runs on its caller alone") {
  ThreadBudget cores(1);
  CHECK_FALSE(cores.try_take());
  std::set<std::thread::id> threads;
  ordered_parallel(
      4, cores, [&](std::size_t) { threads.insert(std::this_thread::get_id()); }, [](std::size_t) {});
  CHECK(threads == std::set<std::thread::id>{std::this_thread::get_id()});
  CHECK(cores.free_cores() == 0);
}

TEST_CASE("consume_while_producing: production on the caller's thread in order, each consume after its produce and "
          "before the production ends, cores given back") {
  ThreadBudget cores(2);
  const std::size_t n = 6;
  const std::thread::id caller = std::this_thread::get_id();
  std::mutex mutex;
  std::condition_variable first_consumed;
  bool consumed_first = false;
  std::vector<std::size_t> order;  // produced indices
  std::vector<std::atomic<int>> produced(n), consumed(n);
  std::atomic<int> prepared{0}, misplaced{0};
  bool overlapped = false;
  consume_while_producing(
      n, cores,
      [&](std::size_t i) {
        if (std::this_thread::get_id() != caller) ++misplaced;
        if (i + 1 == n) {  // the last one waits (at most 10 s) until a consumer has run: the stages overlap
          std::unique_lock<std::mutex> lock(mutex);
          overlapped = first_consumed.wait_for(lock, std::chrono::seconds(10), [&] { return consumed_first; });
        }
        order.push_back(i);
        ++produced[i];
      },
      [&] { ++prepared; },
      [&](std::size_t i) {
        if (produced[i] != 1 || prepared != 1 || std::this_thread::get_id() == caller) ++misplaced;
        ++consumed[i];
        std::lock_guard<std::mutex> lock(mutex);
        consumed_first = true;
        first_consumed.notify_all();
      });
  CHECK(overlapped);
  CHECK(misplaced == 0);
  CHECK(prepared == 1);
  CHECK(order == std::vector<std::size_t>{0, 1, 2, 3, 4, 5});
  for (std::size_t i = 0; i < n; ++i) CHECK(consumed[i] == 1);
  CHECK(cores.free_cores() == 1);
}

TEST_CASE("consume_while_producing: a failing produce ends the production, nothing consumed from it on, its "
          "exception rethrown") {
  ThreadBudget cores(2);
  std::vector<std::atomic<int>> consumed(6);
  std::atomic<int> produced{0};
  CHECK_THROWS_WITH(consume_while_producing(
                        6, cores,
                        [&](std::size_t i) {
                          if (i == 3) throw std::runtime_error("produce 3");
                          ++produced;
                        },
                        [] {}, [&](std::size_t i) { ++consumed[i]; }),
                    "produce 3");
  CHECK(produced == 3);
  for (std::size_t i = 3; i < 6; ++i) CHECK(consumed[i] == 0);
  CHECK(cores.free_cores() == 1);
  CHECK_THROWS_WITH(consume_while_producing(
                        6, cores, [](std::size_t) {}, [] {},
                        [](std::size_t i) {
                          if (i == 4) throw std::runtime_error("consume 4");
                          if (i == 2) throw std::runtime_error("consume 2");
                        }),
                    "consume 2");
  CHECK(cores.free_cores() == 1);
}

TEST_CASE("consume_while_producing: a single core produces everything, then prepares and consumes, on its caller") {
  ThreadBudget cores(1);
  std::vector<std::string> steps;
  std::set<std::thread::id> threads;
  consume_while_producing(
      3, cores,
      [&](std::size_t i) {
        steps.push_back("p" + std::to_string(i));
        threads.insert(std::this_thread::get_id());
      },
      [&] { steps.push_back("prepare"); },
      [&](std::size_t i) {
        steps.push_back("c" + std::to_string(i));
        threads.insert(std::this_thread::get_id());
      });
  CHECK(steps == std::vector<std::string>{"p0", "p1", "p2", "prepare", "c0", "c1", "c2"});
  CHECK(threads == std::set<std::thread::id>{std::this_thread::get_id()});
  CHECK(cores.free_cores() == 0);
}

}  // namespace
}  // namespace mbgen
