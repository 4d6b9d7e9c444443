#include "mbgen/modal_identification/modal_identification.hpp"
#include "mbgen_test/synthetic_frf.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace mbgen {
namespace {

using test::SyntheticFrfSpec;
using test::TrueMode;

std::complex<double> true_pole(const TrueMode& m) {
  const double w = 2 * M_PI * m.f_hz;
  return {-m.zeta * w, w * std::sqrt(1 - m.zeta * m.zeta)};
}

SyntheticFrfSpec two_modes_in_band() {
  SyntheticFrfSpec spec;
  spec.modes = {{80, 0.02, {1.0, 0.6}}, {130, 0.01, {0.5, -1.0}}};
  spec.output_points = {0, 1};
  spec.input_points = {0};
  spec.f_lo = 40;
  spec.f_hi = 200;
  spec.lines = 321;
  return spec;
}

double relative_error(std::complex<double> a, std::complex<double> b) { return std::abs(a - b) / std::abs(b); }

}  // namespace

TEST_CASE("LSFD recovers the residues at exact poles, for receptance, mobility and accelerance", "[modal][lsfd]") {
  for (const FrfQuantity q : {FrfQuantity::Receptance, FrfQuantity::Mobility, FrfQuantity::Accelerance}) {
    SyntheticFrfSpec spec = two_modes_in_band();
    spec.power = frf_quantity_power(q);
    const ModalData data = modal_data({test::synthetic_frf(spec)}, {}, q);
    const std::vector<std::complex<double>> poles{true_pole(spec.modes[0]), true_pole(spec.modes[1])};
    const LsfdResult fit = lsfd(data, poles);
    INFO(frf_quantity_name(q));
    for (std::size_t r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) {
        // The residue of the measured FRF: lambda^p times the receptance's.
        const std::complex<double> expected =
            std::pow(poles[r], spec.power) * test::true_receptance_residue(spec.modes[r], c, 0);
        CHECK(relative_error(fit.residues(static_cast<Eigen::Index>(r), c), expected) < 1e-9);
      }
    CHECK(fit.channel_error.maxCoeff() < 1e-9);
  }
}

TEST_CASE("LSFD's residual terms stand for the modes outside the band", "[modal][lsfd]") {
  SyntheticFrfSpec spec = two_modes_in_band();
  spec.modes.push_back({15, 0.02, {0.8, 0.8}});    // below the band: a mass line there
  spec.modes.push_back({600, 0.02, {1.0, -0.7}});  // above: a stiffness line
  spec.power = 2;
  const ModalData data = modal_data({test::synthetic_frf(spec)}, {}, FrfQuantity::Accelerance);
  const std::vector<std::complex<double>> poles{true_pole(spec.modes[0]), true_pole(spec.modes[1])};
  const LsfdResult with = lsfd(data, poles);
  const LsfdResult without = lsfd(data, poles, LsfdOptions{false, false});
  // Residual terms approximate the outer modes (a mass line and a stiffness line, not exact), so the fit is not
  // exact, but much closer than without them.
  CHECK(with.channel_error.maxCoeff() < 0.01);
  CHECK(without.channel_error.minCoeff() > 5 * with.channel_error.maxCoeff());
  for (std::size_t r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      const std::complex<double> expected = std::pow(poles[r], 2) * test::true_receptance_residue(spec.modes[r], c, 0);
      CHECK(relative_error(with.residues(static_cast<Eigen::Index>(r), c), expected) < 0.01);
    }
  CHECK(without.lower.isZero());
  CHECK(without.upper.isZero());
}

TEST_CASE("LSFD's residual terms are the mass and stiffness lines of the outer modes", "[modal][lsfd]") {
  // One mode below the band alone, then one above alone. In the band 40..200 Hz the 15 Hz mode's receptance
  // phi^2 / (w_r^2 - w^2) is the mass line -phi^2 / w^2 (LR = phi^2 = 0.64) times 1 / (1 - (w_r/w)^2), between 1 and
  // 1 / (1 - (15/40)^2); the 600 Hz mode's is the stiffness line phi^2 / w_r^2 (UR) times 1 / (1 - (w/w_r)^2),
  // between 1 and 1 / (1 - (200/600)^2). The fitted term must lie between.
  for (const bool below : {true, false}) {
    SyntheticFrfSpec spec = two_modes_in_band();
    spec.modes.push_back(below ? TrueMode{15, 0.02, {0.8, 0.8}} : TrueMode{600, 0.02, {0.8, -0.7}});
    const ModalData data = modal_data({test::synthetic_frf(spec)}, {}, FrfQuantity::Receptance);
    const LsfdResult fit = lsfd(data, {true_pole(spec.modes[0]), true_pole(spec.modes[1])});
    const double w600 = 2 * M_PI * 600;
    const double line = below ? 0.64 : 0.64 / (w600 * w600);
    const double fitted = below ? fit.lower[0] : fit.upper[0];
    INFO((below ? "lower " : "upper ") << fitted << " against the line " << line);
    CHECK(fitted > line);
    CHECK(fitted < line / (1 - std::pow(below ? 15.0 / 40 : 200.0 / 600, 2)));
  }
}

}  // namespace mbgen
