#include <mbgen/residuals/same_response.hpp>

#include <catch2/catch.hpp>

#include <string>

#include "evaluator/symbolic_evaluator.hpp"
#include "frontend/parser.hpp"

namespace mbgen::diagnosis {
namespace {

// A table on two legs, `left` and `right`, which share k and c unless a copy `k_copy` replaces k in one leg:
// the two untied variants are mirror images, so the same model; the 2-DOF variant below is not symmetric.
std::string table(const std::string& left_k, const std::string& right_k, const std::string& copy_bounds = "[0, 1e9]",
                  const std::string& copy_name = "k_copy") {
  return "model table\n"
         "param m = 10 \"kg\" estimate in [0, 100]\n"
         "param k = 1e6 \"N/m\" estimate in [0, 1e9]\n"
         "param c = 20 \"N s/m\" estimate in [0, 1e4]\n"
         "param " + copy_name + " = 5e5 \"N/m\" estimate in " + copy_bounds + "\n"
         "ground floor\n"
         "body top {\n  mass m\n  dof x\n}\n"
         "spring left {\n  from floor\n  to top at (0, -0.5, 0)\n  along x\n  stiffness " + left_k + "\n  damping c\n}\n"
         "spring right {\n  from floor\n  to top at (0, 0.5, 0)\n  along x\n  stiffness " + right_k + "\n  damping c\n}\n"
         "input F force on top along x\n"
         "output d displacement of top along x\n";
}

std::string two_masses(const std::string& k1, const std::string& k2) {
  return "model two\n"
         "param m1 = 1 \"kg\" estimate in [0, 100]\n"
         "param m2 = 2 \"kg\" estimate in [0, 100]\n"
         "param k = 1e6 \"N/m\" estimate in [0, 1e9]\n"
         "param k_copy = 5e5 \"N/m\" estimate in [0, 1e9]\n"
         "ground wall\n"
         "body a {\n  mass m1\n  dof x\n}\n"
         "body b {\n  mass m2\n  dof x\n}\n"
         "spring s1 {\n  from wall\n  to a\n  along x\n  stiffness " + k1 + "\n}\n"
         "spring s2 {\n  from wall\n  to b\n  along x\n  stiffness " + k2 + "\n}\n"
         "spring s12 {\n  from a\n  to b\n  along x\n  stiffness k\n}\n"
         "input F force on a along x\n"
         "output d1 displacement of a along x\n"
         "output d2 displacement of b along x\n";
}

std::unique_ptr<mbgen::Model> derive(const std::string& text) {
  return evaluator::make_evaluator(frontend::parse_string(text, "test.mdl"));
}

const std::vector<double> probes = {3.1, 11.7, 37.3, 80.9, 151.3, 310.7, 701.1, 1203.9};

TEST_CASE("same_response: mirror-image untied legs are one model") {
  const auto a = derive(table("k_copy", "k"));
  const auto b = derive(table("k", "k_copy"));
  CHECK(same_response(*a, *b, probes, {"m", "k", "c"}));
}

TEST_CASE("same_response: the copy's name may differ where no fit looks it up") {
  const auto a = derive(table("k_left", "k", "[0, 1e9]", "k_left"));
  const auto b = derive(table("k", "k_right", "[0, 1e9]", "k_right"));
  CHECK(same_response(*a, *b, probes, {"m", "k", "c"}));
  // A start value or a data set's `# set` names it: the two fits would differ.
  CHECK_FALSE(same_response(*a, *b, probes, {"m", "k", "c", "k_left"}));
}

TEST_CASE("same_response: different responses, bounds or signals are different models") {
  const auto a = derive(table("k_copy", "k"));
  SECTION("a stiffness doubled in one leg") { CHECK_FALSE(same_response(*a, *derive(table("k_copy", "2*k")), probes, {})); }
  SECTION("the copy's bounds differ") {
    CHECK_FALSE(same_response(*a, *derive(table("k", "k_copy", "[0, 2e9]")), probes, {}));
  }
  SECTION("untying one of two unlike springs") {
    CHECK_FALSE(same_response(*derive(two_masses("k_copy", "k")), *derive(two_masses("k", "k_copy")), probes, {}));
  }
}

TEST_CASE("probe_frequencies: eight points inside the band of FRF data") {
  FrfData frf;
  frf.file = "x.csv";
  frf.f_hz = Eigen::VectorXd::LinSpaced(100, 0.0, 500.0);
  const std::vector<double> p = probe_frequencies({DataSet(frf)});
  REQUIRE(p.size() == 8);
  for (std::size_t i = 0; i < p.size(); ++i) {
    CHECK(p[i] > 5.0);  // the first line above 0 Hz is 5.05 Hz
    CHECK(p[i] < 500.0);
    if (i > 0) CHECK(p[i] > p[i - 1]);
  }
}

}  // namespace
}  // namespace mbgen::diagnosis
