// The peak lists' rules on hand-made inputs: one peak per 2 %, strongest first, and the outputs a model misses
// more than all others.
#include "diagnosis/engine/prior_peaks.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace mbgen::diagnosis {
namespace {

// Channel "OUTPUT/F" with `n` lines whose normalized residual is `z` on each.
ChannelResidual channel(const std::string& output, double z, int n = 20) {
  ChannelResidual c;
  c.channel = output + "/F";
  c.measured.resize(n);
  c.model.resize(n);
  c.sigma = Eigen::VectorXd::Constant(n, 0.5);
  for (int i = 0; i < n; ++i) {
    c.f_hz.push_back(10.0 * (i + 1));
    c.model[i] = {1.0, 0.0};
    c.measured[i] = c.model[i] + std::sqrt(z) * 0.5;
  }
  return c;
}

}  // namespace

TEST_CASE("peaks within 2 % of a stronger one are the same peak", "[diagnosis]") {
  CHECK(output_of("xs_rear/Fx") == "xs_rear");
  const std::vector<double> peaks = strongest_first({{1.0, 100.0}, {5.0, 200.0}, {3.0, 101.5}, {2.0, 300.0}});
  CHECK(peaks == std::vector<double>{200.0, 101.5, 300.0});  // 100 Hz is 101.5 Hz's, seen again
  std::vector<double> list = {50.0};
  add_distinct(list, 50.9);
  add_distinct(list, 60.0);
  CHECK(list == std::vector<double>{50.0, 60.0});
}

TEST_CASE("an output is missed alone when its excess over the noise is clear and twice every other's", "[diagnosis]") {
  const double z_noise = 1.0;
  CHECK(outputs_missed_alone({channel("a", 3.0), channel("b", z_noise)}) == std::set<std::string>{"a"});
  // Both missed about alike: the structure's, not a sensor's.
  CHECK(outputs_missed_alone({channel("a", 3.0), channel("b", 2.5)}).empty());
  // A small excess (0.3 over the noise) is no finding.
  CHECK(outputs_missed_alone({channel("a", 1.3), channel("b", z_noise)}).empty());
}

}  // namespace mbgen::diagnosis
