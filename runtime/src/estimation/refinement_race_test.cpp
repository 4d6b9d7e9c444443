// The refinement race (refinement_race.hpp): when the follower gives up, and that the answer does not depend on
// whether the leader ran before it or beside it on another thread.
#include "refinement_race.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

using mbgen::estimation::LmOptions;
using mbgen::estimation::RefinementRace;

namespace {

// Costs after step 1, 2, ..., n of a fit descending as c0 exp(-rate * step).
std::vector<double> descent(double c0, double rate, int n) {
  std::vector<double> c;
  for (int i = 1; i <= n; ++i) c.push_back(c0 * std::exp(-rate * i));
  return c;
}

LmOptions solver(int window, int max_iterations) {
  LmOptions o;
  o.continue_window = window;
  o.max_iterations = max_iterations;
  return o;
}

// The first step after which the follower is hopeless (0: never), the leader run to its end first.
int first_hopeless(const std::vector<double>& leader, const std::vector<double>& follower, const LmOptions& o) {
  RefinementRace race;
  for (double c : leader) race.leader_stepped(c);
  race.leader_ended(leader.empty() ? std::numeric_limits<double>::infinity() : leader.back());
  for (std::size_t i = 0; i < follower.size(); ++i) {
    race.follower_stepped(follower[i]);
    if (race.follower_hopeless(o)) return static_cast<int>(i) + 1;
  }
  return 0;
}

}  // namespace

TEST_CASE("a follower whose descent cannot reach the leader's cost by its cap is given up", "[fit][race]") {
  const LmOptions o = solver(50, 200);
  // At its rate of 0.01 per step the follower ends near 2000 exp(-2) = 271 at step 200, far above the leader's 5.
  CHECK(first_hopeless(descent(1000, 0.1, 60), descent(2000, 0.01, 200), o) == 51);  // the first step it is judged
  // The same follower beside a leader that ends at 1000 exp(-0.4) = 670: it can get below that, and runs on.
  CHECK(first_hopeless(descent(1000, 0.002, 200), descent(2000, 0.01, 200), o) == 0);
}

TEST_CASE("a follower below the leader, or still descending fast, is never given up", "[fit][race]") {
  const LmOptions o = solver(50, 200);
  CHECK(first_hopeless(descent(1000, 0.001, 200), descent(900, 0.001, 200), o) == 0);  // below all along
  // Far above, but fast: 1e6 exp(-0.1 step) passes the leader's 50 near step 100.
  CHECK(first_hopeless(std::vector<double>(200, 50.0), descent(1e6, 0.1, 200), o) == 0);
}

TEST_CASE("the follower is judged against the leader's cost after as many steps, or its final one", "[fit][race]") {
  const LmOptions o = solver(10, 40);
  // The follower sits at 100 and descends by 0.001 per step: at step 11 it projects 100 exp(-0.04) = 96 at most.
  // The leader is at 200 until its step 20 and at 10 from there: hopeless only from step 20.
  std::vector<double> leader(19, 200.0);
  leader.resize(40, 10.0);
  CHECK(first_hopeless(leader, descent(100, 0.001, 40), o) == 20);
  // A leader that stopped at step 5 at cost 10: its final cost counts from the first judged step.
  CHECK(first_hopeless(std::vector<double>(5, 10.0), descent(100, 0.001, 40), o) == 11);
}

TEST_CASE("where the follower gives up does not depend on the leader's timing", "[fit][race]") {
  const LmOptions o = solver(10, 40);
  std::vector<double> leader(19, 200.0);
  leader.resize(30, 10.0);
  const std::vector<double> follower = descent(100, 0.001, 40);
  const int sequential = first_hopeless(leader, follower, o);
  REQUIRE(sequential == 20);
  // The leader now runs beside the follower and slower than it: the follower waits for the leader's steps.
  RefinementRace race;
  std::thread lead([&] {
    for (double c : leader) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      race.leader_stepped(c);
    }
    race.leader_ended(leader.back());
  });
  int beside = 0;
  for (std::size_t i = 0; i < follower.size() && beside == 0; ++i) {
    race.follower_stepped(follower[i]);
    if (race.follower_hopeless(o)) beside = static_cast<int>(i) + 1;
  }
  lead.join();
  CHECK(beside == sequential);
}
