#include "mbgen/dynamics/frf.hpp"
#include "mbgen/dynamics/model_modes.hpp"
#include "mbgen/modal_identification/modal_pairing.hpp"
#include "mbgen_test/mdof2.hpp"

#include <Eigen/LU>
#include <catch2/catch.hpp>

#include <cmath>

namespace mbgen {
namespace {

// The model's channels as modal data (H itself is not used by model_modes).
ModalData channels_of(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
  ModalData d;
  d.outputs = outputs;
  d.inputs = inputs;
  for (std::size_t o = 0; o < outputs.size(); ++o)
    for (std::size_t i = 0; i < inputs.size(); ++i)
      d.channels.push_back({static_cast<int>(o), static_cast<int>(i), outputs[o] + "/" + inputs[i]});
  d.f_hz = Eigen::VectorXd::LinSpaced(8, 1, 8);
  d.H = Eigen::MatrixXcd::Zero(8, static_cast<Eigen::Index>(d.channels.size()));
  return d;
}

}  // namespace

TEST_CASE("the model's residues rebuild its FRF (mdof2, displacement, velocity and acceleration outputs)",
          "[modal][pairing]") {
  const test::Mdof2Model model(/*extra_outputs=*/true);
  const Eigen::VectorXd p = model.info().default_values();
  const ModalData data = channels_of({"d1", "d2", "v1", "a2"}, {"F1"});
  const ModelModes modes = model_modes(model, p, data);
  REQUIRE(modes.f_hz.size() == 2);
  ModelMatrices m;
  model.evaluate(p, m);
  const std::vector<Mode> reference = modal_analysis(m.M, m.C, m.K);
  for (std::size_t r = 0; r < 2; ++r) {
    CHECK(modes.f_hz[r] == Approx(reference[r].f_hz).epsilon(1e-10));
    CHECK(modes.zeta[r] == Approx(reference[r].zeta).epsilon(1e-8));
    // The coordinate shape is modal_analysis's up to a complex factor: the same direction (MAC 1).
    const Eigen::VectorXcd shape = modes.shapes.col(static_cast<Eigen::Index>(r));
    REQUIRE(shape.size() == reference[r].shape.size());
    const double mac =
        std::norm(shape.dot(reference[r].shape)) / (shape.squaredNorm() * reference[r].shape.squaredNorm());
    CHECK(mac == Approx(1).epsilon(1e-12));
  }
  // H(s) = D + sum over both members of each pair of residue / (s - lambda): D = 0 except for the acceleration
  // output (a2 = q2'', which feeds the force through M^-1).
  const std::vector<double> f = {20, 95, 180};
  const FrfResult exact = frf(m, f);
  const Eigen::MatrixXd D = m.Ca * m.M.inverse() * m.B;
  for (std::size_t k = 0; k < f.size(); ++k) {
    const std::complex<double> s(0, 2 * M_PI * f[k]);
    for (Eigen::Index c = 0; c < 4; ++c) {
      std::complex<double> h = D(c, 0);
      for (std::size_t r = 0; r < 2; ++r) {
        const std::complex<double> res = modes.residues(static_cast<Eigen::Index>(r), c);
        h += res / (s - modes.lambda[r]) + std::conj(res) / (s - std::conj(modes.lambda[r]));
      }
      CHECK(std::abs(h - exact.H[k](c, 0)) < 1e-9 * std::abs(exact.H[k](c, 0)));
    }
  }
  CHECK(modes.quantity == FrfQuantity::Unknown);  // mixed outputs
  CHECK(model_modes(model, p, channels_of({"d1", "d2"}, {"F1"})).quantity == FrfQuantity::Receptance);
  CHECK(model_modes(model, p, channels_of({"a2"}, {"F1"})).quantity == FrfQuantity::Accelerance);
  CHECK_THROWS_WITH(model_modes(model, p, channels_of({"x9"}, {"F1"})), Catch::Contains("no output named `x9`"));
}

TEST_CASE("identified modes pair with the model's by MAC", "[modal][pairing]") {
  const test::Mdof2Model model;
  const Eigen::VectorXd p = model.info().default_values();
  const ModelModes modes = model_modes(model, p, channels_of({"d1", "d2"}, {"F1"}));
  // Identified modes: the model's residues, the second one rotated in phase (a residue's scale is free) and listed
  // first.
  std::vector<IdentifiedMode> identified(2);
  identified[0].f_hz = modes.f_hz[1] * 1.05;
  identified[0].residues = modes.residues.row(1).transpose() * std::polar(2.0, 0.4);
  identified[1].f_hz = modes.f_hz[0] * 0.95;
  identified[1].residues = modes.residues.row(0).transpose();
  const ModePairing pairing = pair_modes(identified, modes);
  CHECK(pairing.model_mode == std::vector<int>{1, 0});
  CHECK(pairing.best_mac[0] == Approx(1).epsilon(1e-12));
  CHECK(pairing.best_mac[1] == Approx(1).epsilon(1e-12));
  CHECK(pairing.mac(0, 0) < 0.5);
  CHECK(pairing.shared == std::vector<bool>{false, false});
  identified.push_back(identified[1]);  // a third mode that looks like model mode 0 as well
  CHECK(pair_modes(identified, modes).shared == std::vector<bool>{false, true, true});
}

}  // namespace mbgen
