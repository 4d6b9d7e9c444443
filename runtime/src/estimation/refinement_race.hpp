// Two local fits of one problem run side by side, where only the lower result is wanted: the follower gives up as
// soon as it cannot end below the leader. Internal header.
#pragma once

#include "numerics/levenberg_marquardt.hpp"

#include <condition_variable>
#include <cstddef>
#include <limits>
#include <mutex>
#include <vector>

namespace mbgen::estimation {

// The leader's costs step by step, shared with a follower on another thread (or read after the leader ended).
//
// The follower compares itself with the leader after the same number of accepted steps, never with wherever the
// leader happens to be, so that whether and where it gives up depends on the two fits' results alone, not on thread
// timing: it waits for the leader's step when it is ahead. It gives up at step i when its descent over the last
// `window` steps, kept up to its iteration cap, would still leave its cost above the leader's cost at step i (which
// the leader's final cost can only undercut). A fit slowing down is then not let run out its iteration cap for a
// result that at its pace would lose; one that would drop after a plateau is lost with it. The leader must not wait
// on the follower (it never does): start the leader first.
class RefinementRace {
 public:
  // The leader's callbacks: each accepted step's cost, then its final cost (also after a failure: call always).
  void leader_stepped(double cost);
  void leader_ended(double final_cost);

  // The follower's LmOptions::abandoned and on_iteration, for a fit with `options` (its window and cap).
  bool follower_hopeless(const LmOptions& options);
  void follower_stepped(double cost) { follower_.push_back(cost); }

 private:
  // The leader's cost after `steps` accepted steps, or its final cost if it ended before.
  double leader_after(std::size_t steps);

  std::mutex mutex_;
  std::condition_variable stepped_;
  std::vector<double> leader_;  // cost after step 1, 2, ...
  bool leader_done_ = false;
  double leader_final_ = std::numeric_limits<double>::infinity();
  std::vector<double> follower_;  // the follower's own thread only
};

}  // namespace mbgen::estimation
