// The judging rules on small hand-made states: a channel's normalized residual is set line by line (measured =
// model + sqrt(z) sigma), findings are bands on it, and the rules are read off the decisions and their reasons.
#include "diagnosis/engine/judging.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace mbgen::diagnosis {
namespace {

// One channel "y/F" with lines at 10, 20, ..., 10 n Hz whose normalized residuals are `z`.
ChannelResidual channel(const std::vector<double>& z) {
  ChannelResidual c;
  c.channel = "y/F";
  c.data_set = "data.csv";
  const auto n = static_cast<Eigen::Index>(z.size());
  c.measured.resize(n);
  c.model.resize(n);
  c.sigma = Eigen::VectorXd::Constant(n, 0.5);
  for (Eigen::Index i = 0; i < n; ++i) {
    c.f_hz.push_back(10.0 * static_cast<double>(i + 1));
    c.model[i] = {1.0, 1.0};
    c.measured[i] = c.model[i] + std::sqrt(z[static_cast<std::size_t>(i)]) * 0.5;
  }
  return c;
}

Discrepancy finding(double f_lo, double f_hi, double significance, const std::string& kind = "misfit") {
  Discrepancy d;
  d.kind = kind;
  d.channel = "y/F";
  d.data_set = "data.csv";
  d.f_lo = f_lo;
  d.f_hi = f_hi;
  d.f_hz = 0.5 * (f_lo + f_hi);
  d.significance = significance;
  d.text = kind + " near " + std::to_string(static_cast<int>(d.f_hz)) + " Hz";
  return d;
}

// A fitted state: its channel's residuals `z`, its findings, its mean normalized residual and finding threshold 4.
ModelState state(const std::vector<double>& z, std::vector<Discrepancy> findings, double mean_z) {
  ModelState s;
  s.channels = {channel(z)};
  s.residual.discrepancies = std::move(findings);
  s.residual.mean_z = mean_z;
  s.residual.threshold = 4.0;
  return s;
}

CandidateOutcome outcome(const std::string& id, double delta_bic, double validation_nrmse, bool qualifies = true) {
  CandidateOutcome o;
  o.id = id;
  o.delta_bic = delta_bic;
  o.validation_nrmse = validation_nrmse;
  o.qualifies = qualifies;
  return o;
}

TEST_CASE("band_mean_z is the mean normalized residual over a finding's band on its channel", "[judging]") {
  const std::vector<ChannelResidual> channels = {channel({1, 9, 3, 1})};
  CHECK(band_mean_z(channels, finding(15, 35, 6)) == Approx(6.0));  // lines at 20 and 30 Hz
  CHECK(band_mean_z(channels, finding(100, 200, 1)) == -1.0);        // no line in the band
  Discrepancy elsewhere = finding(15, 35, 6);
  elsewhere.channel = "x/F";
  CHECK(band_mean_z(channels, elsewhere) == -1.0);
}

TEST_CASE("a finding still shows unless its band falls below the threshold and its excess over the noise halves",
          "[judging]") {
  const std::vector<ChannelResidual> nominal = {channel({1, 9, 9, 1})};  // the band 15-35 Hz at 9
  const Discrepancy d = finding(15, 35, 9);
  CHECK_FALSE(still_shows(nominal, state({1, 2, 2, 1}, {}, 1.5), d, 4.0));  // 9 -> 2: cleared
  CHECK(still_shows(nominal, state({1, 5, 5, 1}, {}, 2), d, 4.0));          // above the threshold
  const std::vector<ChannelResidual> weak = {channel({1, 5, 5, 1})};
  CHECK(still_shows(weak, state({1, 3.5, 3.5, 1}, {}, 1.5), finding(15, 35, 5), 4.0));  // excess 4 -> 2.5: not halved
  // A parameter pressed against a bound shows while the extended fit presses the same parameter.
  Discrepancy bound = finding(0, 0, 12, "parameter_at_bound");
  bound.parameter = "k";
  Discrepancy again = bound;
  CHECK(still_shows(nominal, state({1, 1, 1, 1}, {again}, 1), bound, 4.0));
  again.parameter = "m";
  CHECK_FALSE(still_shows(nominal, state({1, 1, 1, 1}, {again}, 1), bound, 4.0));
}

TEST_CASE("an extension explains when the excess halves, or partly when a further round may follow", "[judging]") {
  const ModelState current = state({1, 9, 9, 1, 13, 13}, {finding(45, 65, 13), finding(15, 35, 9)}, 7.0);
  const Judgement halved = explains(current, state({1, 2, 2, 1, 6, 6}, {}, 3.0), 1, 3.0);
  CHECK(halved.holds);
  CHECK(halved.why.empty());
  // 7 -> 5 clears the 15-35 Hz finding only: a partial explanation while another round may follow, never at the end.
  const ModelState partly = state({1, 1, 1, 1, 13, 13}, {finding(45, 65, 13)}, 5.0);
  const Judgement partial = explains(current, partly, 1, 3.0);
  CHECK(partial.holds);
  CHECK(partial.why.find("clears: misfit near 25 Hz; a partial explanation") != std::string::npos);
  const Judgement last = explains(current, partly, 0, 3.0);
  CHECK_FALSE(last.holds);
  CHECK(last.why.find("not an explanation") != std::string::npos);
  // Lower overall but clearing nothing: not an explanation.
  CHECK_FALSE(explains(current, state({1, 8, 8, 1, 12, 12}, {}, 6.0), 1, 3.0).holds);
}

TEST_CASE("a sensor's dynamics explain in part only through a finding on their own output", "[judging]") {
  const ModelState current = state({1, 9, 9, 1, 13, 13}, {finding(45, 65, 13), finding(15, 35, 9)}, 7.0);
  const ModelState partly = state({1, 1, 1, 1, 13, 13}, {finding(45, 65, 13)}, 5.0);
  CHECK(explains(current, partly, 1, 3.0, "y").holds);  // the findings lie on channel y/F
  const Judgement elsewhere = explains(current, partly, 1, 3.0, "x");
  CHECK_FALSE(elsewhere.holds);
  CHECK(elsewhere.why.find("not an explanation") != std::string::npos);
  // Halving the excess needs no finding of its own.
  CHECK(explains(current, state({1, 2, 2, 1, 6, 6}, {}, 3.0), 1, 3.0, "x").holds);
}

TEST_CASE("a partial explanation is taken only at a pace that could reach the noise in the rounds left",
          "[judging]") {
  const ModelState current = state({1, 9, 9, 1, 13, 13}, {finding(45, 65, 13), finding(15, 35, 9)}, 7.0);
  // 7 -> 6.5 clears the 15-35 Hz finding. To reach 3 it needs 3.5 more: one round at twice its pace gives 1, four
  // rounds 4.
  const ModelState slowly = state({1, 1, 1, 1, 13, 13}, {finding(45, 65, 13)}, 6.5);
  const Judgement one_left = explains(current, slowly, 1, 3.0);
  CHECK_FALSE(one_left.holds);
  CHECK(one_left.why.find("at that pace the 1 round left could not bring it to 3") != std::string::npos);
  CHECK_FALSE(explains(current, slowly, 3, 3.0).holds);  // 3 rounds: 3 < 3.5
  CHECK(explains(current, slowly, 4, 3.0).holds);
  CHECK(explains(current, slowly, 1, 6.0).holds);  // a lenient end: 0.5 more, and one round gives 1
}

TEST_CASE("the BIC winner must predict the held-back data about as well as the best qualifying candidate",
          "[judging]") {
  const std::vector<CandidateOutcome> close = {outcome("a", -900, 0.014), outcome("b", -600, 0.010)};
  CHECK(predicts_as_well(close, 0).holds);
  const std::vector<CandidateOutcome> apart = {outcome("a", -992, 0.018), outcome("b", -640, 0.0082),
                                               outcome("c", -700, 0.001, false)};  // c does not qualify
  const Judgement j = predicts_as_well(apart, 0);
  CHECK_FALSE(j.holds);
  CHECK(j.why.find("a wins by BIC but b predicts the held-back data 2.2 times better") == 0);
}

TEST_CASE("the best qualifying candidate: the lowest BIC, ties to the first", "[judging]") {
  CHECK(best_qualifying({outcome("a", -100, 0.1), outcome("b", -100.005, 0.1), outcome("c", -50, 0.1)}) == 0);
  CHECK(best_qualifying({outcome("a", -100, 0.1), outcome("b", -200, 0.1, false), outcome("c", -150, 0.1)}) == 2);
  CHECK(best_qualifying({outcome("a", -100, 0.1, false)}) == -1);
}

TEST_CASE("extensions are kept only if together they explain the nominal findings", "[judging]") {
  DiagnosisResult result;
  result.nominal = state({1, 9, 9, 1, 16, 16, 1, 6, 6},
                         {finding(45, 65, 16), finding(15, 35, 9), finding(75, 95, 6)}, 8.0);
  result.selected = {"x"};
  DiagnoseOptions options;  // residual at most 3, at most a third of the findings left
  CHECK(full_explanation(result, state({1, 1, 1, 1, 1, 1, 1, 1, 1}, {}, 1.0), options).holds);
  // One of three left: still kept.
  CHECK(full_explanation(result, state({1, 9, 9, 1, 1, 1, 1, 1, 1}, {}, 2.0), options).holds);
  // The strongest left standing.
  const Judgement strongest = full_explanation(result, state({1, 1, 1, 1, 16, 16, 1, 1, 1}, {}, 2.0), options);
  CHECK_FALSE(strongest.holds);
  REQUIRE(strongest.still.size() == 1);
  CHECK(strongest.still[0]->f_lo == 45);
  // Two of three left.
  const Judgement most = full_explanation(result, state({1, 9, 9, 1, 1, 1, 1, 6, 6}, {}, 2.0), options);
  CHECK_FALSE(most.holds);
  CHECK(most.still.size() == 2);
  CHECK(most.why.find("still shows 2 of the nominal model's 3 findings") != std::string::npos);
  // A residual far above the noise.
  CHECK_FALSE(full_explanation(result, state({1, 1, 1, 1, 1, 1, 1, 1, 1}, {}, 3.5), options).holds);
  // A mode moved where the nominal model had it right.
  Discrepancy moved = finding(195, 205, 5, "frequency_shift");
  moved.f_hz = 200;
  const Judgement mimics = full_explanation(result, state({1, 1, 1, 1, 1, 1, 1, 1, 1}, {moved}, 1.2), options);
  CHECK_FALSE(mimics.holds);
  CHECK(mimics.why.find("moves a mode the nominal model had right") != std::string::npos);
}

TEST_CASE("a further round pursues only the nominal findings still showing", "[judging]") {
  DiagnosisResult result;
  result.nominal = state({1, 9, 9, 1, 16, 16, 1, 1, 1}, {finding(45, 65, 16), finding(15, 35, 9)}, 6.0);
  // The first extension clears the 45-65 Hz finding; the 15-35 Hz one is left for another round.
  CHECK(pending_findings(result, state({1, 9, 9, 1, 1, 1, 1, 1, 1}, {finding(15, 35, 9)}, 3.0)) ==
        std::vector<std::size_t>{1});
  // Both cleared: what the extended model shows near 85 Hz, where the nominal model had no finding, is the
  // extension's own form and leaves nothing pending.
  CHECK(pending_findings(result, state({1, 1, 1, 1, 1, 1, 1, 9, 9}, {finding(75, 95, 9)}, 2.5)).empty());
}

TEST_CASE("the verdict", "[judging]") {
  DiagnosisResult r;
  CHECK(verdict_of(r) == "no_extension_justified");
  r.nominal.residual.discrepancies.push_back(finding(10, 20, 5));
  CHECK(verdict_of(r) == "unexplained");
  r.selected = {"x"};
  CHECK(verdict_of(r) == "extended");
}

}  // namespace
}  // namespace mbgen::diagnosis
