// The real beam FRFs of examples/beam (accelerance, three roving-hammer points, 1 Hz lines, no coherence):
// the six bending modes near 52, 142, 279, 460, 687 and 959 Hz, from the CSV and from the UFF file alike.
#include "mbgen/data/csv.hpp"
#include "mbgen/data/data_set.hpp"
#include "mbgen/modal_identification/modal_identification.hpp"
#include "shape_metrics.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include "mbgen_test/paths.hpp"

namespace mbgen {
namespace {

const std::string kDir = std::string(mbgen_source_dir()) + "/examples/beam/";
const double kPeaks[] = {52, 142, 279, 460, 687, 959};  // the README's peaks, read off the magnitude

ModalIdentification from_csv(FrfQuantity quantity) {
  return identify_modes(modal_data({read_frf_csv(kDir + "frf_beam_3pt.csv")}, {}, quantity));
}

ModalIdentification from_uff() {
  const std::string path = kDir + "measurement.uff";
  const FrfQuantity quantity = uff_frf_quantity(read_uff58(path));
  CHECK(quantity == FrfQuantity::Accelerance);
  return identify_modes(modal_data({std::get<FrfData>(read_data_file(path).content)}, {}, quantity));
}

}  // namespace

TEST_CASE("the FRFs' quantity is the UFF records' whatever the file is called or read from", "[modal][beam]") {
  // `modal` took it from the records only for a name ending in .uff (reading the file a second time): on standard
  // input, through a pipe or as beam.dat the beam came out "unknown", and its modes and their std differed.
  const std::string path = kDir + "measurement.uff";
  std::ifstream in(path, std::ios::binary);
  const FrfData as_dat = std::get<FrfData>(read_data(in, "beam.dat").content);
  CHECK(as_dat.uff_ordinate_type == 12);
  CHECK(uff_frf_quantity(as_dat) == FrfQuantity::Accelerance);
  CHECK(uff_frf_quantity(within_band(as_dat, 100, 200)) == FrfQuantity::Accelerance);
  CHECK(uff_frf_quantity(read_frf_csv(kDir + "frf_beam_3pt.csv")) == FrfQuantity::Unknown);
}

TEST_CASE("the beam's six bending modes, with plausible damping", "[modal][beam]") {
  const ModalIdentification id = from_uff();
  REQUIRE(id.modes.size() == 6);
  for (std::size_t r = 0; r < 6; ++r) {
    const IdentifiedMode& m = id.modes[r];
    INFO("mode " << r + 1 << ": " << m.f_hz << " Hz +- " << m.f_std_hz << ", zeta " << m.zeta << " +- " << m.zeta_std
                 << ", MPC " << m.mpc);
    // Each mode lies within a line (1 Hz) of the peak: the lines are 1 Hz apart, the half-power bands narrower.
    CHECK(std::abs(m.f_hz - kPeaks[r]) < 1.0);
    // Lightly damped, as a free-free steel beam on soft supports is: 0.005 % to 0.5 %, and determined by the data.
    CHECK(m.zeta > 5e-5);
    CHECK(m.zeta < 5e-3);
    CHECK(m.refined);
    CHECK(m.zeta_std < 0.25 * m.zeta);
    CHECK(m.mpc > 0.95);  // nearly real modes: proportional damping
  }
  // Frequencies in the ratios of a uniform free-free beam's bending modes ((2n+1) pi / 2)^2 approximately:
  // 1 : 2.757 : 5.404 : 8.933 : 13.344 : 18.637 (Blevins); a real beam with sensors and suspension is near.
  const double ratios[] = {1, 2.757, 5.404, 8.933, 13.344, 18.637};
  for (std::size_t r = 1; r < 6; ++r) CHECK(id.modes[r].f_hz / id.modes[0].f_hz == Approx(ratios[r]).epsilon(0.01));
  // The synthesized FRFs follow the measured ones within a few per cent over the whole band.
  CHECK(id.fit.channel_error.maxCoeff() < 0.06);
}

TEST_CASE("slow: the beam's CSV and UFF files give the same modes", "[modal][beam][slow]") {
  const ModalIdentification uff = from_uff();
  // The CSV does not say what the FRFs are: told it is accelerance, it is the same data to 10 digits.
  const ModalIdentification csv = from_csv(FrfQuantity::Accelerance);
  REQUIRE(csv.modes.size() == uff.modes.size());
  for (std::size_t r = 0; r < csv.modes.size(); ++r) {
    CHECK(csv.modes[r].f_hz == Approx(uff.modes[r].f_hz).epsilon(1e-8));
    CHECK(csv.modes[r].zeta == Approx(uff.modes[r].zeta).epsilon(1e-6));
    CHECK(modal_detail::shape_mac(csv.modes[r].residues, uff.modes[r].residues) > 1 - 1e-9);
  }
  // Not told, the residual terms take the receptance's form; the frequencies stay within their standard deviations.
  const ModalIdentification unknown = from_csv(FrfQuantity::Unknown);
  REQUIRE(unknown.modes.size() == uff.modes.size());
  for (std::size_t r = 0; r < unknown.modes.size(); ++r)
    CHECK(std::abs(unknown.modes[r].f_hz - uff.modes[r].f_hz) < 2 * uff.modes[r].f_std_hz + 1e-3);
}

}  // namespace mbgen
