#include "mbgen/parallel.hpp"

#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <stdexcept>
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

TEST_CASE("ordered_parallel: the lowest failing index's exception, nothing reported from it on") {
  std::vector<std::size_t> reported;
  const auto run = [&] {
    ordered_parallel(
        6, 2,
        [](std::size_t i) {
          if (i == 4) throw std::runtime_error("task 4");
          if (i == 2) throw std::runtime_error("task 2");
        },
        [&](std::size_t i) { reported.push_back(i); });
  };
  CHECK_THROWS_WITH(run(), "task 2");
  CHECK(reported == std::vector<std::size_t>{0, 1});
}

TEST_CASE("ordered_parallel: no tasks, one worker") {
  int calls = 0;
  ordered_parallel(0, 2, [&](std::size_t) { ++calls; }, [&](std::size_t) { ++calls; });
  ordered_parallel(3, 1, [&](std::size_t) { ++calls; }, [&](std::size_t) { ++calls; });
  CHECK(calls == 6);
}

}  // namespace
}  // namespace mbgen
