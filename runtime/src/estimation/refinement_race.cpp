#include "refinement_race.hpp"

#include <algorithm>
#include <cmath>

namespace mbgen::estimation {

void RefinementRace::leader_stepped(double cost) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    leader_.push_back(cost);
  }
  stepped_.notify_all();
}

void RefinementRace::leader_ended(double final_cost) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    leader_done_ = true;
    leader_final_ = final_cost;
  }
  stepped_.notify_all();
}

double RefinementRace::leader_after(std::size_t steps) {
  std::unique_lock<std::mutex> lock(mutex_);
  stepped_.wait(lock, [&] { return leader_done_ || leader_.size() >= steps; });
  return leader_.size() >= steps ? leader_[steps - 1] : leader_final_;
}

bool RefinementRace::follower_hopeless(const LmOptions& options) {
  const std::size_t steps = follower_.size(), window = static_cast<std::size_t>(std::max(options.continue_window, 1));
  if (steps <= window) return false;
  const double now = follower_[steps - 1], then = follower_[steps - 1 - window];
  if (!(now > 0) || !std::isfinite(then)) return false;
  const int cap = options.continue_gain > 0 ? std::max(options.iteration_cap, options.max_iterations)
                                            : options.max_iterations;
  const double left = std::max(cap - static_cast<int>(steps), 0);
  const double rate = std::log(then / now) / static_cast<double>(window);  // per step, in ln(cost)
  const double leader = leader_after(steps);
  return std::isfinite(leader) && std::log(now) - rate * left > std::log(leader);
}

}  // namespace mbgen::estimation
