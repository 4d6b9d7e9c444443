#include "mbgen/modal_identification/modal_identification.hpp"
#include "mbgen_test/synthetic_frf.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace mbgen {
namespace {

using test::SyntheticFrfSpec;
using test::TrueMode;

// Three well-separated modes seen at three points, force at one.
SyntheticFrfSpec three_modes() {
  SyntheticFrfSpec spec;
  spec.modes = {{60, 0.02, {1.0, 0.8, 0.3}}, {150, 0.01, {0.7, -0.5, 1.0}}, {310, 0.015, {0.4, 1.0, -0.9}}};
  spec.output_points = {0, 1, 2};
  spec.input_points = {0};
  spec.f_lo = 2;
  spec.f_hi = 400;
  spec.lines = 400;
  return spec;
}

// The pole of order `order` nearest to f, or nullptr.
const DiagramPole* nearest(const StabilizationDiagram& d, int order, double f) {
  const DiagramPole* best = nullptr;
  for (const DiagramPole& p : d.poles)
    if (p.order == order && (!best || std::abs(p.f_hz - f) < std::abs(best->f_hz - f))) best = &p;
  return best;
}

}  // namespace

TEST_CASE("LSCF on noise-free FRFs finds every mode's pole at a sufficient order", "[modal][lscf]") {
  const SyntheticFrfSpec spec = three_modes();
  const ModalData data = modal_data({test::synthetic_frf(spec)}, {});
  LscfOptions options;
  options.max_order = 30;
  const StabilizationDiagram diagram = lscf(data, options);
  CHECK(diagram.references == 1);
  CHECK(diagram.orders.size() == 30);
  for (const TrueMode& m : spec.modes) {
    const DiagramPole* p = nearest(diagram, 30, m.f_hz);
    REQUIRE(p != nullptr);
    INFO("mode " << m.f_hz << " Hz: found " << p->f_hz << " Hz, zeta " << p->zeta);
    CHECK(std::abs(p->f_hz / m.f_hz - 1) < 1e-6);
    CHECK(std::abs(p->zeta / m.zeta - 1) < 1e-4);
    // The operational shape is the mode shape (force at point 0: the outputs see phi_o phi_0).
    Eigen::VectorXcd expected(3);
    for (int o = 0; o < 3; ++o) expected[o] = m.shape[static_cast<std::size_t>(o)];
    const double mac = std::norm(expected.dot(p->shape)) / (expected.squaredNorm() * p->shape.squaredNorm());
    CHECK(mac > 1 - 1e-8);
  }
}

TEST_CASE("LSCF takes the smaller side of a full FRF matrix as references", "[modal][lscf]") {
  SyntheticFrfSpec spec = three_modes();
  spec.input_points = {0, 2};  // 3 outputs x 2 inputs
  const ModalData data = modal_data({test::synthetic_frf(spec)}, {});
  LscfOptions options;
  options.max_order = 16;
  const StabilizationDiagram diagram = lscf(data, options);
  CHECK(diagram.references == 2);
  CHECK_FALSE(diagram.transposed);
  for (const TrueMode& m : spec.modes) {
    const DiagramPole* p = nearest(diagram, 16, m.f_hz);
    REQUIRE(p != nullptr);
    CHECK(std::abs(p->f_hz / m.f_hz - 1) < 1e-6);
    CHECK(std::abs(p->zeta / m.zeta - 1) < 1e-4);
    CHECK(p->shape.size() == 3);
  }

  spec.output_points = {1, 2};
  spec.input_points = {0, 1, 2};  // 2 outputs x 3 inputs: rows are the inputs
  const StabilizationDiagram transposed = lscf(modal_data({test::synthetic_frf(spec)}, {}), options);
  CHECK(transposed.references == 2);
  CHECK(transposed.transposed);
  const DiagramPole* p = nearest(transposed, 16, 150);
  REQUIRE(p != nullptr);
  CHECK(std::abs(p->f_hz / 150 - 1) < 1e-6);
  CHECK(p->shape.size() == 3);
}

TEST_CASE("LSCF refuses an order the band's lines cannot support", "[modal][lscf]") {
  SyntheticFrfSpec spec = three_modes();
  spec.lines = 40;
  const ModalData data = modal_data({test::synthetic_frf(spec)}, {});
  LscfOptions options;
  options.max_order = 21;
  CHECK_THROWS_WITH(lscf(data, options), Catch::Contains("needs at least 42 lines") && Catch::Contains("holds 40"));
  // `modal --max-order 2000000000`: twice the order overflowed an int in the message ("at least -294967296 lines").
  options.max_order = 2000000000;
  CHECK_THROWS_WITH(lscf(data, options), Catch::Contains("needs at least 4000000000 lines"));
  options.max_order = 0;  // the default fits the band
  CHECK(lscf(data, options).orders.back() == 10);
}

}  // namespace mbgen
