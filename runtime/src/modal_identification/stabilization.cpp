// The stabilization diagram's labels, and the choice of the physical poles from it.
#include "mbgen/modal_identification/modal_identification.hpp"
#include "shape_metrics.hpp"
#include "numerics/constants.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

namespace mbgen {

namespace {

using modal_detail::shape_mac;
using Stability = DiagramPole::Stability;

using numerics::kTwoPi;
constexpr double kUserWindow = 0.02;  // select_poles_near: relative distance in frequency
constexpr int kMinFullyStable = 1;    // a physical pole's cluster holds at least this many fully stable poles

// Distance of two poles of the diagram: relative distance of the complex poles plus the shapes' disagreement.
double pole_distance(const DiagramPole& a, const DiagramPole& b) {
  return std::abs(a.lambda - b.lambda) / std::max(std::abs(a.lambda), std::abs(b.lambda)) +
         (1 - shape_mac(a.shape, b.shape));
}

bool physical_damping(const DiagramPole& p, const StabilizationCriteria& c) {
  return p.zeta > 0 && p.zeta <= c.max_zeta;
}

// Neighbours of candidate poles: for each, the others of other orders within `radius`.
class Neighbours {
 public:
  Neighbours(const StabilizationDiagram& diagram, std::vector<int> candidates, double radius)
      : diagram_(diagram), candidates_(std::move(candidates)) {
    std::sort(candidates_.begin(), candidates_.end(), [&](int a, int b) {
      return diagram.poles[static_cast<std::size_t>(a)].f_hz < diagram.poles[static_cast<std::size_t>(b)].f_hz ||
             (diagram.poles[static_cast<std::size_t>(a)].f_hz == diagram.poles[static_cast<std::size_t>(b)].f_hz &&
              a < b);
    });
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
      const DiagramPole& p = pole(candidates_[i]);
      std::vector<std::pair<int, double>> list;
      for (std::size_t j = 0; j < candidates_.size(); ++j) {
        if (j == i) continue;
        const DiagramPole& q = pole(candidates_[j]);
        // |dlambda| / |lambda| >= |df| / f: poles further apart in frequency cannot be neighbours.
        if (std::abs(q.f_hz - p.f_hz) > radius * std::max(p.f_hz, q.f_hz)) {
          if (j > i) break;
          continue;
        }
        if (q.order == p.order) continue;
        const double d = pole_distance(p, q);
        if (d <= radius) list.emplace_back(candidates_[j], d);
      }
      lists_[candidates_[i]] = std::move(list);
    }
  }

  const std::vector<int>& candidates() const { return candidates_; }

  // The seed and, for every other order, its nearest neighbour still in `pool`.
  std::vector<int> cluster(int seed, const std::map<int, bool>& pool) const {
    std::map<int, std::pair<int, double>> best;  // order -> (pole, distance)
    for (const auto& [q, d] : lists_.at(seed)) {
      if (!pool.at(q)) continue;
      const int order = pole(q).order;
      auto it = best.find(order);
      if (it == best.end() || d < it->second.second) best[order] = {q, d};
    }
    std::vector<int> members{seed};
    for (const auto& [order, entry] : best) members.push_back(entry.first);
    return members;
  }

 private:
  const DiagramPole& pole(int i) const { return diagram_.poles[static_cast<std::size_t>(i)]; }
  const StabilizationDiagram& diagram_;
  std::vector<int> candidates_;
  std::map<int, std::vector<std::pair<int, double>>> lists_;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

SelectedPole summarize(const StabilizationDiagram& diagram, std::vector<int> members) {
  std::sort(members.begin(), members.end());
  std::vector<double> f, zeta;
  for (int i : members) {
    f.push_back(diagram.poles[static_cast<std::size_t>(i)].f_hz);
    zeta.push_back(diagram.poles[static_cast<std::size_t>(i)].zeta);
  }
  SelectedPole s;
  s.f_hz = median(f);
  s.zeta = median(zeta);
  const double w = kTwoPi * s.f_hz;
  s.lambda = {-s.zeta * w, w * std::sqrt(std::max(0.0, 1 - s.zeta * s.zeta))};
  s.support = static_cast<int>(members.size());
  s.members = std::move(members);
  return s;
}

void sort_by_frequency(std::vector<SelectedPole>& poles) {
  std::stable_sort(poles.begin(), poles.end(),
                   [](const SelectedPole& a, const SelectedPole& b) { return a.f_hz < b.f_hz; });
}

std::string hz(double f) {
  std::ostringstream s;
  s << std::setprecision(6) << f << " Hz";
  return s.str();
}

}  // namespace

void label_stability(StabilizationDiagram& diagram, const StabilizationCriteria& criteria) {
  // Poles are stored by order: [begin, end) of each order.
  std::map<int, std::pair<std::size_t, std::size_t>> range;
  for (std::size_t i = 0; i < diagram.poles.size(); ++i) {
    auto it = range.find(diagram.poles[i].order);
    if (it == range.end())
      range[diagram.poles[i].order] = {i, i + 1};
    else
      it->second.second = i + 1;
  }
  for (std::size_t o = 0; o < diagram.orders.size(); ++o) {
    const auto here = range.find(diagram.orders[o]);
    if (here == range.end()) continue;
    const auto below = o > 0 ? range.find(diagram.orders[o - 1]) : range.end();
    for (std::size_t i = here->second.first; i < here->second.second; ++i) {
      DiagramPole& p = diagram.poles[i];
      p.stability = Stability::New;
      if (below == range.end()) continue;
      const DiagramPole* q = nullptr;
      for (std::size_t j = below->second.first; j < below->second.second; ++j)
        if (!q || std::abs(diagram.poles[j].f_hz - p.f_hz) < std::abs(q->f_hz - p.f_hz)) q = &diagram.poles[j];
      if (!q || std::abs(p.f_hz - q->f_hz) > criteria.frequency * q->f_hz) continue;
      const bool damping = std::abs(p.zeta - q->zeta) <= criteria.damping * std::abs(q->zeta);
      const bool shape = 1 - shape_mac(p.shape, q->shape) <= criteria.shape;
      p.stability = damping && shape ? Stability::Stable
                    : damping        ? Stability::FrequencyDamping
                    : shape          ? Stability::FrequencyShape
                                     : Stability::Frequency;
    }
  }
}

std::vector<SelectedPole> select_physical_poles(const StabilizationDiagram& diagram, const SelectionOptions& options) {
  // Candidates: stable in frequency and in damping or shape. With one row the shape says nothing (a scalar), so
  // damping is required.
  const bool shapes_informative = !diagram.poles.empty() && diagram.poles.front().shape.size() > 1;
  std::vector<int> candidates;
  for (std::size_t i = 0; i < diagram.poles.size(); ++i) {
    const Stability s = diagram.poles[i].stability;
    const bool stable_enough = s == Stability::Stable || s == Stability::FrequencyDamping ||
                               (shapes_informative && s == Stability::FrequencyShape);
    if (stable_enough && physical_damping(diagram.poles[i], options.criteria))
      candidates.push_back(static_cast<int>(i));
  }
  const Neighbours neighbours(diagram, candidates, options.criteria.frequency + options.criteria.shape);
  std::map<int, bool> pool;
  for (int c : neighbours.candidates()) pool[c] = true;
  const int min_support = std::max(
      3, static_cast<int>(std::ceil(options.min_orders_fraction * static_cast<double>(diagram.orders.size()))));
  const auto fully_stable = [&](const std::vector<int>& members) {
    int count = 0;
    for (int i : members) count += diagram.poles[static_cast<std::size_t>(i)].stability == Stability::Stable;
    return count;
  };

  std::vector<SelectedPole> selected;
  std::map<int, bool> seeds = pool;  // poles that may still seed a cluster
  for (;;) {
    // The seed with the largest cluster; ties go to the lower frequency (candidates are sorted by it).
    std::vector<int> best;
    for (int c : neighbours.candidates()) {
      if (!pool[c] || !seeds[c]) continue;
      std::vector<int> members = neighbours.cluster(c, pool);
      if (members.size() > best.size()) best = std::move(members);
    }
    if (static_cast<int>(best.size()) < min_support) break;
    if (fully_stable(best) < kMinFullyStable) {  // frequent but never fully stable: not a mode; its seed is spent
      seeds[best.front()] = false;
      continue;
    }
    for (int i : best) pool[i] = false;
    selected.push_back(summarize(diagram, best));
  }
  sort_by_frequency(selected);
  return selected;
}

std::vector<SelectedPole> select_poles_near(const StabilizationDiagram& diagram, const std::vector<double>& f_hz,
                                            const SelectionOptions& options) {
  const StabilizationCriteria& c = options.criteria;
  const int highest = diagram.orders.empty() ? 0 : diagram.orders.back();
  // Tiers of trust: fully stable, stable in frequency, any pole of the highest order.
  const auto tier_of = [&](const DiagramPole& p) {
    if (!physical_damping(p, c) && !(p.order == highest && p.zeta > 0)) return 3;
    if (p.stability == Stability::Stable && physical_damping(p, c)) return 0;
    if (p.stability != Stability::New && physical_damping(p, c)) return 1;
    return p.order == highest && p.zeta > 0 ? 2 : 3;
  };
  std::vector<SelectedPole> selected;
  std::map<int, double> taken;  // pole index -> the frequency that took it
  for (const double target : f_hz) {
    bool found = false;
    for (int tier = 0; tier < 3 && !found; ++tier) {
      std::vector<int> candidates;
      for (std::size_t i = 0; i < diagram.poles.size(); ++i) {
        const DiagramPole& p = diagram.poles[i];
        if (tier_of(p) <= tier && std::abs(p.f_hz - target) <= kUserWindow * target)
          candidates.push_back(static_cast<int>(i));
      }
      if (candidates.empty()) continue;
      const Neighbours neighbours(diagram, candidates, c.frequency + c.shape);
      std::map<int, bool> pool;
      for (int i : candidates) pool[i] = true;
      std::vector<int> best;
      double best_offset = 0;
      for (int i : neighbours.candidates()) {
        std::vector<int> members = neighbours.cluster(i, pool);
        const double offset = std::abs(diagram.poles[static_cast<std::size_t>(i)].f_hz - target);
        if (members.size() > best.size() || (members.size() == best.size() && offset < best_offset)) {
          best = std::move(members);
          best_offset = offset;
        }
      }
      for (int i : best) {
        const auto it = taken.find(i);
        if (it != taken.end())
          throw std::invalid_argument(hz(it->second) + " and " + hz(target) + " select the same pole");
      }
      for (int i : best) taken[i] = target;
      SelectedPole s = summarize(diagram, best);
      s.user_selected = true;
      selected.push_back(std::move(s));
      found = true;
    }
    if (!found) throw std::invalid_argument("no pole of the stabilization diagram lies within 2 % of " + hz(target));
  }
  sort_by_frequency(selected);
  return selected;
}

}  // namespace mbgen
