#include "mbgen/modal_identification/modal_identification.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

namespace mbgen {
namespace {

using Stability = DiagramPole::Stability;

DiagramPole pole(int order, double f, double zeta, Eigen::VectorXcd shape) {
  DiagramPole p;
  p.order = order;
  p.f_hz = f;
  p.zeta = zeta;
  const double w = 2 * M_PI * f;
  p.lambda = {-zeta * w, w * std::sqrt(1 - zeta * zeta)};
  p.shape = std::move(shape);
  return p;
}

Eigen::VectorXcd shape(double a, double b) {
  Eigen::VectorXcd s(2);
  s << a, b;
  return s;
}

// A hand-made diagram of orders 1..20: a physical mode at 100 Hz from order 3 on (small scatter), a second one at
// 102 Hz with another shape from order 6 on, and at every order a spurious pole at a random frequency and damping.
StabilizationDiagram hand_made() {
  StabilizationDiagram d;
  d.lo_hz = 10;
  d.hi_hz = 300;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> f(20, 280), z(0.001, 0.3), jitter(-1, 1);
  for (int n = 1; n <= 20; ++n) {
    d.orders.push_back(n);
    std::vector<DiagramPole> poles;
    if (n >= 3)
      poles.push_back(pole(n, 100 * (1 + 2e-4 * jitter(rng)), 0.01 * (1 + 0.01 * jitter(rng)), shape(1, 0.5)));
    if (n >= 6)
      poles.push_back(pole(n, 102 * (1 + 2e-4 * jitter(rng)), 0.02 * (1 + 0.01 * jitter(rng)), shape(-0.4, 1)));
    poles.push_back(pole(n, f(rng), z(rng), shape(jitter(rng), jitter(rng))));
    std::sort(poles.begin(), poles.end(), [](const DiagramPole& a, const DiagramPole& b) { return a.f_hz < b.f_hz; });
    for (const DiagramPole& p : poles) d.poles.push_back(p);
  }
  return d;
}

const DiagramPole* find(const StabilizationDiagram& d, int order, double f) {
  for (const DiagramPole& p : d.poles)
    if (p.order == order && std::abs(p.f_hz - f) < 0.01 * f) return &p;
  return nullptr;
}

}  // namespace

TEST_CASE("stability labels compare each pole with the nearest of the order below", "[modal][stabilization]") {
  StabilizationDiagram d;
  d.orders = {1, 2};
  d.poles = {pole(1, 100, 0.010, shape(1, 0.5)),    pole(1, 200, 0.02, shape(1, 1)),
             pole(2, 100.5, 0.0104, shape(1, 0.5)),  // f, zeta, shape all within the criteria
             pole(2, 150, 0.02, shape(1, 1)),        // nothing near below
             pole(2, 201, 0.03, shape(1, 1.1)),      // f and shape, not damping
             pole(2, 201.5, 0.0201, shape(1, -1))};  // f and damping, not shape
  label_stability(d);
  CHECK(d.poles[0].stability == Stability::New);
  CHECK(d.poles[2].stability == Stability::Stable);
  CHECK(d.poles[3].stability == Stability::New);
  CHECK(d.poles[4].stability == Stability::FrequencyShape);
  CHECK(d.poles[5].stability == Stability::FrequencyDamping);
  d.poles[2] = pole(2, 102, 0.01, shape(1, 0.5));  // 2 % off: not stable in frequency
  label_stability(d);
  CHECK(d.poles[2].stability == Stability::New);
  d.poles[2] = pole(2, 100.5, 0.01, shape(1, 0.2));
  d.poles[4] = pole(2, 201, 0.03, shape(0.4, 1.1));
  label_stability(d);
  CHECK(d.poles[2].stability == Stability::FrequencyDamping);
  CHECK(d.poles[4].stability == Stability::Frequency);
}

TEST_CASE("automatic selection keeps clusters of stable poles and drops spurious ones", "[modal][stabilization]") {
  StabilizationDiagram d = hand_made();
  label_stability(d);
  CHECK(find(d, 10, 100)->stability == Stability::Stable);
  CHECK(find(d, 10, 102)->stability == Stability::Stable);
  const std::vector<SelectedPole> selected = select_physical_poles(d);
  REQUIRE(selected.size() == 2);
  CHECK(selected[0].f_hz == Approx(100).epsilon(3e-4));
  CHECK(selected[0].zeta == Approx(0.01).epsilon(0.01));
  CHECK(selected[0].support == 17);  // stable from order 4 (order 3 is its first appearance) to 20
  CHECK(selected[1].f_hz == Approx(102).epsilon(3e-4));
  CHECK(selected[1].zeta == Approx(0.02).epsilon(0.01));
  CHECK(selected[1].support == 14);
  CHECK(std::abs(selected[0].lambda) == Approx(2 * M_PI * selected[0].f_hz));
  for (const SelectedPole& s : selected) CHECK_FALSE(s.user_selected);

  // A mode seen at too few orders is not physical.
  SelectionOptions strict;
  strict.min_orders_fraction = 0.8;  // 16 of 20 orders
  const std::vector<SelectedPole> one = select_physical_poles(d, strict);
  REQUIRE(one.size() == 1);
  CHECK(one[0].f_hz == Approx(100).epsilon(3e-4));
}

TEST_CASE("selection by frequency takes the best-supported poles near each frequency", "[modal][stabilization]") {
  StabilizationDiagram d = hand_made();
  label_stability(d);
  const std::vector<SelectedPole> s = select_poles_near(d, {102.5, 99});
  REQUIRE(s.size() == 2);
  CHECK(s[0].f_hz == Approx(100).epsilon(3e-4));
  CHECK(s[1].f_hz == Approx(102).epsilon(3e-4));
  CHECK(s[0].user_selected);
  CHECK(s[1].support == 14);
  // Near no stable pole: the nearest pole of the highest order, if within 2 %.
  const DiagramPole* last = nullptr;
  for (const DiagramPole& p : d.poles)
    if (p.order == 20 && std::abs(p.f_hz - 101) > 5) last = &p;
  REQUIRE(last != nullptr);
  const std::vector<SelectedPole> lone = select_poles_near(d, {last->f_hz * 1.01});
  REQUIRE(lone.size() == 1);
  CHECK(lone[0].f_hz == last->f_hz);
  CHECK_THROWS_WITH(select_poles_near(d, {5}), Catch::Contains("within 2 % of 5 Hz"));
  CHECK_THROWS_WITH(select_poles_near(d, {100, 100.1}), Catch::Contains("select the same pole"));
}

}  // namespace mbgen
