// Local fits already run, kept for the fits of one model that come after (FitOptions::memo). Internal header.
//
// A diagnosis fits each candidate several times: its screening fit starts at the current estimate, the priors and
// its alternative starts, and its full searches start at the same points (then at random ones); a refit with
// undetermined parameters held may repeat starts too. A local fit is a function of its start and its problem, so
// the repeats (12 % of a spindle diagnosis's Levenberg-Marquardt iterations) gave bit-identical results; the memo
// returns the earlier one instead.
//
// The key is exact: the start and the free parameters compared as they are, and a 64-bit hash of everything else a
// local fit depends on: the values of the parameters not fitted (from the prior), the free parameters' transforms
// (their bounds and scale), the solver's options, and the residuals at the start of every residual kind the fit
// uses (they carry the data, the weighting and the model). The caller scopes a memo to one model: the hash cannot
// tell two models apart whose residuals agree at one point but not elsewhere.
#pragma once

#include "numerics/levenberg_marquardt.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <tuple>
#include <vector>

namespace mbgen::estimation {

// FNV-1a over the bytes of what is fed in, in order.
class Fingerprint {
 public:
  void add(const void* data, std::size_t bytes);
  void add(double v) { add(&v, sizeof v); }
  void add(int v) { add(&v, sizeof v); }
  void add(const Eigen::VectorXd& v);
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ULL;
};

class LocalFitMemo {
 public:
  struct Key {
    std::vector<int> free;
    std::vector<std::uint64_t> start;  // the bits of each coordinate
    std::uint64_t fingerprint = 0;
    bool operator<(const Key& o) const {
      return std::tie(fingerprint, free, start) < std::tie(o.fingerprint, o.free, o.start);
    }
  };

  std::optional<LmResult> find(const Key& key) const;
  // Keeps the first result stored under a key (a repeat computed meanwhile is the same).
  void store(const Key& key, const LmResult& result);

 private:
  mutable std::mutex mutex_;
  std::map<Key, LmResult> runs_;
};

}  // namespace mbgen::estimation
