// The output correlations by FFT against the direct sums they stand for, and response_data's bookkeeping.
#include "mbgen/data/data_error.hpp"
#include "mbgen/modal_identification/output_only_modal.hpp"

#include <catch2/catch.hpp>

#include <limits>
#include <random>

using namespace mbgen;

namespace {

TimeRecord record(const std::string& file, const std::vector<std::string>& names, Eigen::Index samples,
                  unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  TimeRecord r;
  r.file = file;
  r.t = Eigen::VectorXd::LinSpaced(samples, 0.0, static_cast<double>(samples - 1) * 1e-3);
  for (const std::string& n : names) {
    Signal s{n, Eigen::VectorXd(samples)};
    for (Eigen::Index k = 0; k < samples; ++k) s.values[k] = 3 + normal(rng);  // an offset, removed
    r.signals.push_back(s);
  }
  return r;
}

}  // namespace

TEST_CASE("output correlations by FFT equal the direct sums, over two records and chosen references",
          "[output-only]") {
  const ResponseData data = response_data({record("a.csv", {"x", "y", "z", "F"}, 700, 1),
                                           record("b.csv", {"x", "y", "z", "F"}, 300, 2)},
                                          {{"F"}, {"z", "x"}});
  REQUIRE(data.channels == std::vector<std::string>{"x", "y", "z"});
  REQUIRE(data.references == std::vector<int>{2, 0});
  REQUIRE(data.notes.size() == 1);
  CHECK(std::abs(data.records[0].col(0).mean()) < 1e-12);
  const Eigen::Index lags = 40;
  const std::vector<Eigen::MatrixXd> R = output_correlations(data, lags);
  REQUIRE(R.size() == static_cast<std::size_t>(lags));
  for (Eigen::Index k = 0; k < lags; ++k) {
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(3, 2);
    double count = 0;
    for (const Eigen::MatrixXd& y : data.records) {
      const Eigen::Index n = y.rows();
      for (Eigen::Index t = 0; t + k < n; ++t)
        for (int j = 0; j < 2; ++j)
          sum.col(j) += y.row(t + k).transpose() * y(t, data.references[static_cast<std::size_t>(j)]);
      count += static_cast<double>(n - k);
    }
    INFO("lag " << k);
    CHECK((R[static_cast<std::size_t>(k)] - sum / count).norm() < 1e-12 * (sum / count).norm() + 1e-14);
  }
}

TEST_CASE("response_data refuses records that cannot be one data set", "[output-only]") {
  CHECK_THROWS_AS(response_data({}), DataError);
  CHECK_THROWS_WITH(response_data({record("a.csv", {"x", "y"}, 300, 1), record("b.csv", {"x", "z"}, 300, 2)}),
                    Catch::Contains("b.csv") && Catch::Contains("differ"));
  CHECK_THROWS_WITH(response_data({record("a.csv", {"x", "y"}, 100, 1)}), Catch::Contains("too short"));
  CHECK_THROWS_WITH(response_data({record("a.csv", {"x"}, 300, 1)}, {{"x"}, {}}), Catch::Contains("no response"));
  CHECK_THROWS_WITH(response_data({record("a.csv", {"x", "y"}, 300, 1)}, {{}, {"q"}}),
                    Catch::Contains("reference q"));
  TimeRecord nan = record("n.csv", {"x", "y"}, 300, 1);
  nan.signals[1].values[7] = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(response_data({nan}), Catch::Contains("n.csv") && Catch::Contains("non-finite"));
}
