#include "mbgen/dynamics/sampling.hpp"

#include "mbgen/dynamics/dynamics_error.hpp"

#include <catch2/catch.hpp>

TEST_CASE("uniform sampling interval") {
  Eigen::VectorXd t(5);
  t << 0.0, 0.001, 0.002, 0.003, 0.004;
  CHECK(mbgen::uniform_sample_interval(t) == Approx(0.001).epsilon(1e-14));
  // Times printed with few digits still count as uniform.
  t << 1.2345, 1.2355, 1.23649, 1.2375, 1.2385;
  CHECK(mbgen::uniform_sample_interval(t, 0.02) == Approx(0.001).epsilon(1e-12));
}

TEST_CASE("non-uniform or broken time columns are rejected") {
  Eigen::VectorXd t(5);
  t << 0.0, 0.001, 0.002, 0.0035, 0.0045;  // a jump
  CHECK_THROWS_AS(mbgen::uniform_sample_interval(t), mbgen::DynamicsError);
  CHECK_THROWS_WITH(mbgen::uniform_sample_interval(t), Catch::Contains("not uniformly sampled: sample 1"));
  t << 0.0, 0.001, 0.001, 0.002, 0.003;
  CHECK_THROWS_WITH(mbgen::uniform_sample_interval(t), Catch::Contains("not increasing at sample 2"));
  CHECK_THROWS_WITH(mbgen::uniform_sample_interval(Eigen::VectorXd::Zero(1)), Catch::Contains("at least two"));
  t << 0.0, 0.001, std::nan(""), 0.003, 0.004;
  CHECK_THROWS_WITH(mbgen::uniform_sample_interval(t), Catch::Contains("sample 2 is not finite"));
}
