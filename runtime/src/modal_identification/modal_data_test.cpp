#include "mbgen/data/data_error.hpp"
#include "mbgen/modal_identification/modal_identification.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

namespace mbgen {
namespace {

FrfData frf(const std::string& file, const std::vector<std::string>& names, int lines, double df, double f0 = 0) {
  FrfData d;
  d.file = file;
  d.f_hz = Eigen::VectorXd::LinSpaced(lines, f0, f0 + df * (lines - 1));
  for (const std::string& n : names) {
    FrfChannel c;
    c.output = n.substr(0, n.find('/'));
    c.input = n.substr(n.find('/') + 1);
    c.values = Eigen::VectorXcd::Constant(lines, {1.0, 0.5});
    d.channels.push_back(c);
  }
  return d;
}

}  // namespace

TEST_CASE("modal_data joins files on one axis, cuts the band and drops 0 Hz", "[modal][data]") {
  FrfData a = frf("a.csv", {"y1/u1", "y2/u1"}, 101, 1.0);  // 0..100 Hz
  FrfData b = frf("b.csv", {"y1/u2"}, 101, 1.0);
  b.channels[0].values[20] = {7, 8};
  const ModalData all = modal_data({a, b}, {}, FrfQuantity::Accelerance);
  CHECK(all.f_hz.size() == 100);
  CHECK(all.f_hz[0] == 1.0);
  CHECK(all.channels.size() == 3);
  CHECK(all.outputs == std::vector<std::string>{"y1", "y2"});
  CHECK(all.inputs == std::vector<std::string>{"u1", "u2"});
  CHECK(all.channels[2].name == "y1/u2");
  CHECK(all.channels[2].output == 0);
  CHECK(all.channels[2].input == 1);
  CHECK(all.H(19, 2) == std::complex<double>(7, 8));  // line 20 Hz
  CHECK(all.quantity == FrfQuantity::Accelerance);
  CHECK(all.files == std::vector<std::string>{"a.csv", "b.csv"});

  const ModalData band = modal_data({a, b}, {10, 20});
  CHECK(band.f_hz.size() == 11);
  CHECK(band.f_hz[0] == 10.0);
  CHECK(band.f_hz[10] == 20.0);
  CHECK(band.H(10, 2) == std::complex<double>(7, 8));
}

TEST_CASE("modal_data names the file for every data problem", "[modal][data]") {
  const FrfData a = frf("a.csv", {"y1/u1"}, 101, 1.0);
  CHECK_THROWS_AS(modal_data({}, {}), DataError);
  CHECK_THROWS_WITH(modal_data({a}, {200, 300}), Catch::StartsWith("a.csv: error: the band 200..300 Hz holds 0 lines"));
  CHECK_THROWS_WITH(modal_data({a}, {10, 14}),
                    Catch::Contains("holds 5 lines above 0 Hz; modal analysis needs at least 8"));
  CHECK_THROWS_WITH(modal_data({a, frf("b.csv", {"y1/u1"}, 101, 1.0)}, {}),
                    Catch::StartsWith("b.csv: error: channel y1/u1 is given twice"));
  CHECK_THROWS_WITH(modal_data({a, frf("c.csv", {"y2/u1"}, 101, 1.0, 0.5)}, {}),
                    Catch::StartsWith("c.csv: error: its frequencies in the band differ from those of a.csv"));
  FrfData nan = a;
  nan.channels[0].values[30] = {std::numeric_limits<double>::quiet_NaN(), 0};
  CHECK_THROWS_WITH(modal_data({nan}, {}), Catch::StartsWith("a.csv: error: channel y1/u1 is not finite at 30 Hz"));
  CHECK_NOTHROW(modal_data({nan}, {40, 100}));  // outside the band it does not matter
  // A channel zero in the band, or too small to square (its error came out 0, a perfect fit, with status 0).
  FrfData zero = frf("z.csv", {"y1/u1", "y2/u1"}, 101, 1.0);
  zero.channels[1].values.setZero();
  zero.channels[1].values[0] = {1, 0};  // at 0 Hz, outside every band
  CHECK_THROWS_WITH(modal_data({zero}, {}),
                    Catch::StartsWith("z.csv: error: channel y2/u1 is zero at every line in the band: it has no "
                                      "modes"));
  FrfData tiny = frf("t.csv", {"y1/u1"}, 101, 1.0);
  tiny.channels[0].values *= 1e-200;
  CHECK_THROWS_WITH(modal_data({tiny}, {}),
                    Catch::StartsWith("t.csv: error: channel y1/u1 is too small to analyse: its largest magnitude in "
                                      "the band, 1.118033989e-200, is below 1e-150"));
  tiny.channels[0].values *= 1e60;  // 1e-140: squares 1e-280, normal doubles
  CHECK_NOTHROW(modal_data({tiny}, {}));
}

TEST_CASE("frf quantities have names and powers of i w", "[modal][data]") {
  CHECK(std::string(frf_quantity_name(FrfQuantity::Mobility)) == "mobility");
  CHECK(frf_quantity_power(FrfQuantity::Receptance) == 0);
  CHECK(frf_quantity_power(FrfQuantity::Mobility) == 1);
  CHECK(frf_quantity_power(FrfQuantity::Accelerance) == 2);
  CHECK(frf_quantity_power(FrfQuantity::Unknown) == 0);
}

}  // namespace mbgen
