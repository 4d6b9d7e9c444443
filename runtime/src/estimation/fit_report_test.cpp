// The mbgen-fit/1 JSON and the report directory.
#include "mbgen_test/estimation.hpp"

#include "mbgen/estimation/fit_report.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include "mbgen_test/paths.hpp"

using namespace mbgen;

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Fixture {
  test::LinearModel model = [] {
    test::Mdof2Values prior;
    prior.k11 *= 1.1;
    prior.m2 *= 0.95;
    test::LinearModel m = test::mdof2_model(prior);
    m.parameter("k_unused", 1.0, ParameterRole::Estimate);  // appears nowhere: unidentifiable
    return m;
  }();
  std::vector<DataSet> data;
  FitResult result;
  Fixture() {
    std::mt19937 rng(31);
    FrfData frf = test::mdof2_frf_data(test::Mdof2Values{}, Eigen::VectorXd::LinSpaced(561, 20, 300), 0.01, rng);
    frf.file = "frf.csv";
    data.emplace_back(frf);
    TimeRecord rec = test::mdof2_time_record(test::Mdof2Values{}, 400, 1.0 / 2000, 0.01, rng);
    rec.file = "time.csv";
    data.emplace_back(rec);
    FitOptions o;
    o.starts = 2;
    result = fit(model, data, o);
  }
};

}  // namespace

TEST_CASE("the fit JSON follows mbgen-fit/1", "[fit][json]") {
  const Fixture f;
  const std::string text = fit_result_json(f.result);
  CHECK(text == fit_result_json(f.result));  // deterministic
  const nlohmann::json j = nlohmann::json::parse(text);
  CHECK(j["schema"] == "mbgen-fit/1");
  CHECK(j["model"] == "mdof2");
  CHECK(j["data"] == nlohmann::json::array({"frf.csv", "time.csv"}));
  CHECK(j["method"] == "mixed-output-error");
  REQUIRE(j["parameters"].size() == 8);
  CHECK(j["parameters"]["k11"]["identifiable"] == true);
  CHECK(j["parameters"]["k11"]["value"].get<double>() == Approx(1.38e6).epsilon(0.01));
  CHECK(j["parameters"]["k11"]["std"].get<double>() > 0);
  CHECK(j["parameters"]["k_unused"]["identifiable"] == false);
  CHECK(j["parameters"]["k_unused"]["std"].is_null());
  CHECK(j["parameters"]["k_unused"]["value"] == 1.0);
  CHECK_FALSE(j["parameters"].contains("c12"));  // fixed: not a candidate
  CHECK(j["fit"]["nrmse"].get<double>() > 0);
  CHECK(j["fit"]["bic"].is_number());
  REQUIRE(j["modes"].size() == 2);
  CHECK(j["modes"][0]["f_hz"].get<double>() == Approx(89.72).epsilon(0.01));
  CHECK(j["correlation"]["matrix"].size() == 7);
}

TEST_CASE("the report directory has Markdown, data, scripts and (with gnuplot) SVG plots", "[fit][report]") {
  const Fixture f;
  const std::filesystem::path dir = std::filesystem::path(mbgen_binary_dir()) / "fit_report_test_out";
  std::filesystem::remove_all(dir);
  write_fit_report(dir.string(), f.model, f.data, f.result);
  const std::string md = slurp(dir / "report.md");
  CHECK(md.find("| k11 |") != std::string::npos);
  CHECK(md.find("**no** (kept at prior)") != std::string::npos);
  for (const char* stem : {"set1_d1_F1", "set1_d2_F1", "set2_d1", "set2_d2"}) {
    INFO(stem);
    CHECK(std::filesystem::exists(dir / (std::string(stem) + ".dat")));
    CHECK(std::filesystem::exists(dir / (std::string(stem) + ".gp")));
    CHECK(md.find(std::string(stem) + ".svg") != std::string::npos);
  }
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    CHECK(std::filesystem::file_size(dir / "set1_d1_F1.svg") > 1000);
    CHECK(std::filesystem::exists(dir / "set1_d1_F1_residual.svg"));
    CHECK(md.find("not rendered") == std::string::npos);
  }
  // Deterministic: a second run gives the same files.
  const std::string dat = slurp(dir / "set1_d1_F1.dat");
  write_fit_report(dir.string(), f.model, f.data, f.result);
  CHECK(slurp(dir / "report.md") == md);
  CHECK(slurp(dir / "set1_d1_F1.dat") == dat);
}

TEST_CASE("the report's confidence bands, residual tests and validation section", "[fit][report]") {
  Fixture f;
  f.result.residual_test_lags = 25;
  f.result.residual_tests = residual_tests(f.model, f.data, f.result.values, 25);
  f.result.validation = validation_scores(f.model, f.data, f.result.values);
  const std::filesystem::path dir = std::filesystem::path(mbgen_binary_dir()) / "fit_report_test_validation";
  std::filesystem::remove_all(dir);
  write_fit_report(dir.string(), f.model, f.data, f.result, f.data);
  const std::string md = slurp(dir / "report.md");
  // The fit has a covariance: the Bode overlays carry the band (columns 10 to 13) and the report says what it is.
  CHECK(md.find("The shaded band around the estimate's Bode curves") != std::string::npos);
  CHECK(slurp(dir / "set1_d1_F1.dat").find("|H|-2std |H|+2std phase-2std phase+2std") != std::string::npos);
  CHECK(slurp(dir / "set1_d1_F1.gp").find("using 1:10:11 with filledcurves") != std::string::npos);
  // The record's two outputs: a whiteness and a cross-correlation row each, and a plot each.
  CHECK(md.find("## Residual tests") != std::string::npos);
  CHECK(md.find("| `time.csv` | d1 | cross-correlation with F1 |") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "resid2_d2.gp"));
  CHECK(md.find("## Validation on other data") != std::string::npos);
  CHECK(md.find("| `frf.csv` | d2/F1 |") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "validate2_d1.dat"));
  // The fit's own data scored: the fit % the fit itself reached, high.
  for (const ValidationScore& v : f.result.validation)
    for (const ChannelValidation& c : v.channels) CHECK(c.fit_percent > 90);
  const std::string json = fit_result_json(f.result);
  CHECK(json.find("\"residual_tests\"") != std::string::npos);
  CHECK(json.find("\"validation\"") != std::string::npos);

  // Without a covariance: no band, and the report says so.
  f.result.estimated.clear();
  f.result.covariance.resize(0, 0);
  write_fit_report(dir.string(), f.model, f.data, f.result);
  CHECK(slurp(dir / "report.md").find("No confidence band on the Bode curves") != std::string::npos);
  CHECK(slurp(dir / "set1_d1_F1.gp").find("filledcurves") == std::string::npos);
}
